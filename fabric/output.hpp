#pragma once
// The fabric results file (docs/formats/fabric.md): one HDF5 group per checkpoint under
// /checkpoints, with a CSV beside it holding one row per checkpoint.

#include "common/h5/file.hpp"
#include "common/h5/provenance.hpp"
#include "fabric/measures.hpp"

#include <span>
#include <string>
#include <vector>

namespace aniso::fabric {

inline constexpr std::int64_t fabric_schema_version = 1;

/// The group name of a checkpoint: its file name without folder and extension.
std::string checkpoint_stem(const std::string& path);

/// InputError (exit 2) naming the checkpoints when two inputs share a stem (the results store
/// one group per stem), before anything is measured.
void require_distinct_stems(const std::vector<std::string>& paths);

/// CSV header and rows (numbers only, after the source path column), shared with the series table.
std::vector<std::string> column_names();
std::vector<std::string> column_units(); ///< the unit of each column, in the same order
std::vector<double> column_values(const FabricMeasures& measures);

/// Writes the /checkpoints/<stem> group of one checkpoint (serial file).
void write_checkpoint_group(h5::Group& checkpoints, const FabricMeasures& measures);

/// Writes a CSV atomically: header line, then one line per row (source path, then the values).
void write_csv(const std::string& path, const std::vector<std::string>& header,
               const std::vector<std::pair<std::string, std::vector<double>>>& rows);

/// Writes <h5_path> (root attributes, provenance, /checkpoints) and the CSV at <csv_path>, each
/// atomically, from rank 0 (collective; the same error on every rank if it fails). Stems must be
/// unique (InputError otherwise).
void write_fabric_results(const std::string& h5_path, const std::string& csv_path,
                          std::span<const FabricMeasures> measures, const h5::Provenance& provenance,
                          const mpi::Comm& comm);

/// Creates a results file with its schema attributes and provenance (serial); shared with series.
h5::File create_results_file(const std::string& path, const std::string& description,
                             const h5::Provenance& provenance);

} // namespace aniso::fabric
