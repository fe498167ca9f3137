// aniso-dem: periodic-cell DEM. `prepare` builds a dense isotropic assembly,
// `load` runs biaxial plane strain at constant mean stress from it, `hold` measures
// how static a checkpoint is and `relax` makes a loosely relaxed checkpoint static;
// `import` and `export` carry assemblies from and to other codes and ParaView; `replicate` tiles a
// checkpoint into copies of its cell.
#include "common/cli.hpp"
#include "common/error.hpp"
#include "common/h5/checkpoint.hpp"
#include "common/memory.hpp"
#include "dem/commands.hpp"
#include "dem/config.hpp"
#include "dem/interop/replicate.hpp"
#include "dem/interop/transfer_commands.hpp"
#include "dem/io/parameters.hpp"

#include <fmt/format.h>

#include <optional>

namespace {

int run_dem(int argc, char** argv, const aniso::mpi::Comm& comm) {
  using namespace aniso;
  CLI::App app{"aniso-dem: periodic-cell DEM of spheres and ovoids (Kuhn, Sun & Wang 2015, section 2)"};
  cli::CommonOptions options;
  cli::add_common_options(app, options, "aniso-dem");
  app.require_subcommand(1);
  auto* prepare = app.add_subcommand("prepare", "build a dense isotropic assembly consolidated to p0 "
                                                "(writes <output_dir>/prepared.h5)");
  auto* load =
      app.add_subcommand("load", "biaxial plane strain at constant mean stress from a prepared assembly "
                                 "(writes <output_dir>/load_NNN.h5 and history.h5)");
  auto* hold = app.add_subcommand("hold", "hold a checkpoint's cell fixed for --steps time steps and report "
                                          "the drift of p (a static state keeps its stress)");
  auto* relax = app.add_subcommand(
      "relax", "relax a checkpoint at its own loading control to the verified equilibrium of "
               "dem.equilibrium and write it to --output (a static state for the probes)");
  auto* consolidate = app.add_subcommand(
      "consolidate", "consolidate an imported assembly isotropically to dem.prepare.confining_pressure with "
                     "the loading's friction, relaxed to the verified equilibrium (--output: a prepared "
                     "assembly for load)");
  auto* import =
      app.add_subcommand("import", "an assembly from a LAMMPS/LIGGGHTS data file or YADE's text export "
                                   "(spheres) or a DEMPLA D-file (spheres or ovoids), with the "
                                   "tangential forces of a contact dump, as a checkpoint (--output)");
  auto* export_ = app.add_subcommand(
      "export", "a checkpoint as a LAMMPS data file (and contact dump), or as XDMF for ParaView "
                "(particles and force chains)");
  auto* replicate = app.add_subcommand(
      "replicate", "a checkpoint tiled periodically into n1 x n2 x n3 copies of its cell, every particle and "
                   "contact with its state, as a checkpoint (--output) for load, relax and every stage");
  dem::interop::ReplicateOptions replicate_options;
  replicate->add_option("--input", replicate_options.input, "checkpoint to tile, e.g. prepared.h5 (HDF5)")
      ->required();
  replicate
      ->add_option("--output", replicate_options.output, "tiled checkpoint to write (HDF5; not the input)")
      ->required();
  replicate
      ->add_option(
          "--copies", replicate_options.copies,
          "n1,n2,n3: copies of the cell along x, y and z, each >= 1 (particle ids: id + copy index x "
          "N, copy index i + n1 (j + n2 k))")
      ->required();
  replicate->add_flag("--overwrite", replicate_options.overwrite, "replace --output if it exists");
  replicate->fallthrough();
  dem::interop::ImportOptions import_options;
  import->add_option("--input", import_options.input, "LAMMPS data file, YADE text export or DEMPLA D-file")
      ->required();
  import->add_option("--format", import_options.format, "lammps (default), yade or dempla")
      ->check(CLI::IsMember({"lammps", "yade", "dempla"}));
  import->add_option("--d50", import_options.d50,
                     "scale every length so that the median diameter by volume is this [m] (DEMPLA's "
                     "samples have D50 = 1)");
  import->add_option("--cell", import_options.cell, "yade: the periodic cell's lengths LX,LY,LZ [m]")
      ->expected(3)
      ->delimiter(',');
  import->add_option("--contacts", import_options.contacts,
                     "LAMMPS `dump local` file with each contact's tangential force (keeps a static state "
                     "static)");
  import->add_option(
      "--contact-columns", import_options.contact_columns,
      "1-based columns I,J,T of the two ids and the first tangential force component in "
      "--contacts; T < 0: force on the second id (aniso's export: 1,2,6; LIGGGHTS pair/gran/local "
      "id force_tangential: 1,2,4)");
  import->add_option("--output", import_options.output, "checkpoint to write (HDF5; must not exist)")
      ->required();
  import->fallthrough();
  dem::interop::ExportOptions export_options;
  export_->add_option("--input", export_options.input, "checkpoint (HDF5)")->required();
  export_
      ->add_option("--format", export_options.format,
                   "lammps, xdmf or dempla (default: xdmf for an --output ending in .xmf, else lammps)")
      ->check(CLI::IsMember({"lammps", "xdmf", "dempla"}));
  export_->add_option("--output", export_options.output, "LAMMPS data file, .xmf for xdmf, or DEMPLA D-file")
      ->required();
  export_->add_option(
      "--contacts", export_options.contacts,
      "lammps: also write every contact as a `dump local` file (id1 id2 fnx fny fnz ftx fty ftz)");
  export_->fallthrough();
  std::string input;
  std::string output;
  dem::HoldOptions hold_options;
  dem::LoadOptions load_options;
  relax->add_option("--input", input, "checkpoint to relax (HDF5)")->required();
  relax->add_option("--output", output, "relaxed checkpoint to write (HDF5; not the input)")->required();
  dem::RelaxOptions relax_options; // relax and consolidate
  relax->add_flag("--resume", relax_options.resume,
                  "continue from the _interrupted file of a relax stopped on SIGTERM or killed");
  relax->fallthrough();
  consolidate->add_option("--input", input, "checkpoint to consolidate, e.g. from aniso-dem import (HDF5)")
      ->required();
  consolidate->add_option("--output", output, "prepared assembly to write (HDF5; must not exist)")
      ->required();
  consolidate->add_flag("--resume", relax_options.resume,
                        "continue from the _interrupted file of a consolidate stopped on SIGTERM or killed");
  consolidate->fallthrough();
  hold->add_option("--input", input, "checkpoint to hold (HDF5)")->required();
  hold->add_option("--steps", hold_options.steps, "time steps to hold")
      ->required()
      ->check(CLI::Range(1, 2000000000));
  hold->add_option("--csv", hold_options.csv,
                   "write p, q and the equilibrium ratios at every control update here");
  hold->add_option("--max-drift", hold_options.max_drift,
                   "exit 5 if |p - p_start| / p_start exceeds this at any sample (0: report only)")
      ->check(CLI::NonNegativeNumber);
  hold->fallthrough();
  load->add_option("--input", input, "prepared assembly, or with --resume a load checkpoint (HDF5)")
      ->required();
  load->add_flag("--resume", load_options.resume, "continue a loading run from one of its checkpoints");
  load->add_flag(
      "--overwrite", load_options.overwrite,
      "replace the loading run already in dem.output_dir (its history and load_NNN.h5 are removed)");
  // How often prepare and load keep the state in progress, for a resume after a kill.
  const CLI::Validator keep_minutes(
      [](std::string& text) {
        double minutes = 0;
        return CLI::detail::lexical_cast(text, minutes) && minutes >= 0 ? std::string()
                                                                        : "expected minutes, 0 or more";
      },
      "MINUTES");
  dem::PrepareOptions prepare_options;
  prepare->add_flag(
      "--resume", prepare_options.resume,
      "continue a prepare stopped on SIGTERM or killed from the pieces it kept in dem.output_dir");
  prepare
      ->add_option("--keep-every", prepare_options.keep_every_minutes,
                   "keep the compaction or consolidation in progress every MINUTES of wall time, so that a "
                   "prepare killed without SIGTERM loses no more (0: at every control update)")
      ->check(keep_minutes)
      ->capture_default_str();
  for (CLI::App* relaxing : {relax, consolidate}) {
    relaxing
        ->add_option(
            "--keep-every", relax_options.keep_every_minutes,
            "keep the relaxation's state as the _interrupted file every MINUTES of wall time, so that "
            "a run killed without SIGTERM loses no more (0: at every control update)")
        ->check(keep_minutes)
        ->capture_default_str();
  }
  load->add_option("--keep-every", load_options.keep_every_minutes,
                   "keep the loading's state as load_interrupted.h5 (with the history) every MINUTES of wall "
                   "time, so that a load killed without SIGTERM loses no more (0: at every control update)")
      ->check(keep_minutes)
      ->capture_default_str();
  prepare->fallthrough();
  load->fallthrough();
  if (auto code = cli::parse(app, argc, argv, comm)) return *code;

  const auto source = cli::load_config(options);
  config::Reader reader(source.table, source.name);
  reader.tolerate_sections({"fabric", "probe", "voxel", "lbm", "workflow"});
  dem::DemConfig config = dem::io::read_dem_config(reader);
  if (cli::finish_config(reader, options, comm)) return 0;
  const Logger logger = make_logger("aniso-dem", comm, options.log_level);

  std::optional<h5::Checkpoint> checkpoint;
  if (load->parsed() || hold->parsed() || relax->parsed() || consolidate->parsed()) {
    // Each rank reads its slab of the rows; the simulation sends every particle to its rank.
    checkpoint = h5::read_checkpoint(input, comm, h5::RowShare::slab);
    logger->info("input '{}': {} particles, {} contacts, step {}", input, checkpoint->totals.particles,
                 checkpoint->totals.contacts, checkpoint->step);
    dem::io::adopt_checkpoint_values(config, reader, *checkpoint, input);
  }
  require_input(!(load_options.resume && load_options.overwrite),
                "load: --resume continues the run in dem.output_dir and --overwrite "
                "replaces it; give one of them");
  // The particle arrays alone hold 26 doubles per particle; contacts, neighbour lists and the
  // checkpoint copy at least as much again, so 512 bytes is a floor, not an estimate.
  constexpr double min_bytes_per_particle = 512;
  require_memory(min_bytes_per_particle * static_cast<double>(config.particles.count) / comm.size(),
                 fmt::format("dem: {} particles on {} rank(s) (at least {:.0f} bytes each)",
                             config.particles.count, comm.size(), min_bytes_per_particle),
                 "lower dem.particles.count or spread the run over more nodes");
  // import, export and replicate take their particles from the files they read, not the configuration.
  if (import->parsed() || export_->parsed() || replicate->parsed())
    logger->info("configuration is valid");
  else
    logger->info("configuration is valid ({} particles, seed {})", config.particles.count, config.seed);
  if (options.dry_run) return 0;

  if (export_->parsed()) return dem::interop::run_export(export_options, logger, comm);
  if (replicate->parsed())
    return dem::interop::run_replicate(replicate_options, config, reader, cli::join_command_line(argc, argv),
                                       logger, comm);
  const dem::CommandContext context{config, reader, cli::join_command_line(argc, argv), logger, comm};
  if (hold->parsed()) return dem::run_hold(context, *checkpoint, input, hold_options);
  if (import->parsed())
    return dem::interop::run_import(import_options, config, reader, context.command_line, logger, comm);
  if (relax->parsed()) return dem::run_relax(context, *checkpoint, input, output, relax_options);
  if (consolidate->parsed()) return dem::run_consolidate(context, *checkpoint, input, output, relax_options);
  if (prepare->parsed()) return dem::run_prepare(context, prepare_options);
  return dem::run_load(context, *checkpoint, input, load_options);
}

} // namespace

int main(int argc, char** argv) {
  return aniso::cli::run(argc, argv, "aniso-dem", run_dem);
}
