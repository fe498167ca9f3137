#pragma once
// The `import` and `export` commands of aniso-dem: assemblies in and out of other codes' files
// (dem/interop/assembly_text.hpp, dem/interop/contact_dump.hpp) and particles out to ParaView
// (dem/interop/particle_xdmf.hpp).

#include "common/config.hpp"
#include "common/h5/provenance.hpp"
#include "common/log.hpp"
#include "common/mpi.hpp"
#include "dem/config.hpp"

#include <string>
#include <vector>

namespace aniso::dem::interop {

struct ImportOptions {
  std::string input;             ///< LAMMPS data file or YADE text export
  std::string format = "lammps"; ///< "lammps", "yade" or "dempla"
  std::vector<double> cell;      ///< YADE: the periodic cell's lengths [m]
  double d50 = 0;                ///< > 0: scale every length so that D50 by volume is this [m]
  std::string contacts;          ///< optional `dump local` file with tangential forces
  std::string contact_columns = "1,2,6";
  std::string output; ///< checkpoint to write (must not exist)
};

struct ExportOptions {
  std::string input;    ///< checkpoint
  std::string format;   ///< "lammps", "xdmf" or "dempla"; empty: xdmf for a .xmf output, else lammps
  std::string output;   ///< data file or .xmf
  std::string contacts; ///< lammps: also write the contacts as a `dump local` file here
};

/// Reads the other code's files, writes the checkpoint (collective) and logs what was matched.
int run_import(const ImportOptions& options, DemConfig& config, config::Reader& reader,
               const std::string& command_line, const Logger& logger, const mpi::Comm& comm);

/// Writes the checkpoint's particles (and contacts) in the chosen format, on rank 0.
int run_export(const ExportOptions& options, const Logger& logger, const mpi::Comm& comm);

/// Creates the folder a file is to be written in (and its parents), if it has one.
void create_parent_folder(const std::string& path);

} // namespace aniso::dem::interop
