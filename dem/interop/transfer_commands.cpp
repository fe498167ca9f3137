#include "dem/interop/transfer_commands.hpp"

#include "common/error.hpp"
#include "common/h5/checkpoint.hpp"
#include "common/output_folder.hpp"
#include "dem/interop/assembly_text.hpp"
#include "dem/interop/contact_dump.hpp"
#include "dem/interop/import.hpp"
#include "dem/interop/particle_xdmf.hpp"

#include <fmt/format.h>

#include <filesystem>

namespace aniso::dem::interop {

void create_parent_folder(const std::string& path) {
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  if (!folder.empty()) create_output_folder(folder.string());
}

int run_import(const ImportOptions& options, DemConfig& config, config::Reader& reader,
               const std::string& command_line, const Logger& logger, const mpi::Comm& comm) {
  require_input(
      !std::filesystem::exists(options.output),
      fmt::format("import: --output '{}' exists: give a new file (nothing is overwritten)", options.output));
  require_input(
      options.format == "lammps" || options.format == "yade" || options.format == "dempla",
      fmt::format("import: --format '{}': expected lammps (LAMMPS/LIGGGHTS data file), yade "
                  "(YADE's text export of spheres) or dempla (DEMPLA/OVAL D-file of spheres or ovoids)",
                  options.format));
  require_input(options.format == "yade" || options.cell.empty(),
                "import: --cell is for --format yade (a LAMMPS data file carries its box)");
  require_input(options.d50 >= 0, fmt::format("import: --d50 {:g}, expected > 0 [m]", options.d50));
  ImportedAssembly assembly;
  if (options.format == "lammps")
    assembly = read_lammps_data(options.input);
  else if (options.format == "dempla")
    assembly = read_dempla_dfile(options.input);
  else
    assembly = read_yade_text(options.input, options.cell.size() == 3
                                                 ? Vec3(options.cell[0], options.cell[1], options.cell[2])
                                                 : Vec3::Zero());
  // DEMPLA's files have no units (its samples: D50 = 1); the tangential forces of a dump would
  // not scale with the lengths, so the two are not combined.
  require_input(options.d50 == 0 || options.contacts.empty(),
                "import: --d50 rescales the assembly, and a contact dump's forces would not match it: "
                "give one or the other");
  if (options.d50 > 0) assembly = scaled_to_d50(std::move(assembly), options.d50);
  std::vector<DumpedContact> dumped;
  if (!options.contacts.empty())
    dumped = read_contact_dump(options.contacts, parse_contact_columns(options.contact_columns));
  ImportSummary summary;
  const h5::Checkpoint checkpoint =
      import_assembly(assembly, options.contacts.empty() ? nullptr : &dumped, config, reader, summary);
  create_parent_folder(options.output);
  const auto provenance =
      h5::make_provenance("aniso-dem import", reader.effective_toml(), command_line, comm);
  h5::write_checkpoint(options.output, rows_for_rank(checkpoint, comm), provenance, comm);
  const Vec3& lengths = checkpoint.cell.lengths;
  logger->info("import of '{}' ({}): {} {} in a {:.6g} x {:.6g} x {:.6g} m cell, D50 {:.6g} m, density "
               "{:g} kg/m^3, time step {:.4g} s; {} contacts by aniso's contact law",
               options.input, options.format, checkpoint.particles.size(),
               assembly.aspect_ratio == 1.0
                   ? std::string("spheres")
                   : fmt::format("ovoids of aspect ratio {:g}", assembly.aspect_ratio),
               lengths.x(), lengths.y(), lengths.z(), summary.d50, summary.density, checkpoint.time_step,
               summary.contacts);
  if (!options.contacts.empty()) {
    logger->info(
        "contact dump '{}': {} tangential forces adopted ({} capped at the Coulomb limit); {} dumped "
        "pairs are apart in aniso; {} aniso contacts have no dumped row (tangential force 0)",
        options.contacts, summary.dumped_matched, summary.sliding, summary.dumped_apart,
        summary.without_dumped);
    if (summary.dumped_apart + summary.without_dumped > 0)
      logger->warn(
          "the dump and aniso's contacts differ in {} pairs: the other code's contact law or "
          "positions differ from aniso's; the state may not be static (check it with aniso-dem hold)",
          summary.dumped_apart + summary.without_dumped);
  }
  logger->info("wrote {}: p = {:.9g} Pa, unbalanced-force ratio {:.3e}, kinetic/elastic {:.3e}",
               options.output, summary.mean_stress, checkpoint.unbalanced_force_ratio,
               checkpoint.kinetic_elastic_ratio);
  return 0;
}

namespace {

// The format a --format names, or that the output's name implies; a text format under a name
// that says XDMF or HDF5 is refused, so that no file holds other content than its name says
// (the XDMF writer itself insists on ".xmf").
std::string export_format(const ExportOptions& options) {
  const std::string extension = std::filesystem::path(options.output).extension().string();
  if (options.format.empty()) return extension == ".xmf" ? "xdmf" : "lammps";
  require_input(options.format == "xdmf" || (extension != ".xmf" && extension != ".h5"),
                fmt::format("export: --format {} writes a text file, but --output '{}' is named as {}: give "
                            "another name{}",
                            options.format, options.output, extension == ".xmf" ? "XDMF" : "HDF5",
                            extension == ".xmf" ? ", or --format xdmf (or no --format) for ParaView" : ""));
  return options.format;
}

} // namespace

int run_export(const ExportOptions& given, const Logger& logger, const mpi::Comm& comm) {
  ExportOptions options = given;
  options.format = export_format(given);
  require_input(options.format == "lammps" || options.format == "xdmf" || options.format == "dempla",
                fmt::format("export: --format '{}': expected lammps (data file, and with --contacts a "
                            "`dump local` of the contact forces), xdmf (particles and force chains for "
                            "ParaView) or dempla (a DEMPLA/OVAL D-file of spheres or ovoids, its start file)",
                            options.format));
  require_input(options.format == "lammps" || options.contacts.empty(),
                "export: --contacts is for --format lammps (the XDMF output holds the contacts)");
  const h5::Checkpoint checkpoint = h5::read_checkpoint(options.input, comm);
  if (!comm.is_root()) return 0;
  create_parent_folder(options.output);
  if (options.format == "xdmf") {
    const ParticleXdmfSummary written = write_particle_xdmf(checkpoint, options.input, options.output);
    logger->info("export of '{}': {} particles and {} contacts ({} strong) in {} and {}", options.input,
                 written.particles, written.contacts, written.strong_contacts, written.xdmf_path,
                 written.data_path);
    return 0;
  }
  if (options.format == "dempla") {
    write_dempla_dfile(options.output, checkpoint);
    logger->info("export of '{}': {} particles in DEMPLA D-file {} (lengths in metres)", options.input,
                 checkpoint.particles.size(), options.output);
    return 0;
  }
  write_lammps_data(options.output, checkpoint);
  logger->info("export of '{}': {} spheres in LAMMPS data file {}", options.input,
               checkpoint.particles.size(), options.output);
  if (!options.contacts.empty()) {
    create_parent_folder(options.contacts);
    write_contact_dump(options.contacts, checkpoint);
    logger->info("export of '{}': {} contacts in `dump local` file {} (id1 id2 fnx fny fnz ftx fty ftz)",
                 options.input, checkpoint.contacts.size(), options.contacts);
  }
  return 0;
}

} // namespace aniso::dem::interop
