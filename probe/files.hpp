#pragma once
// The probe's files (docs/formats/probe.md):
//  - a fork file, probe_<stem>_fork<N>.h5 (N = 0..6, 0 the reference): one fork's stress
//    readings, the settings that produced it and the checkpoint it came from (path, content hash);
//  - the collected result, probe_<stem>.h5 (+ probe_<stem>.csv): /stiffness with
//    Q_plus, Q_minus, C, D (3x3, Pa), the moduli and checks, attributes K_C, source,
//    source_hash, strain and increment; and the seven forks under /forks.
// Writers are serial (call them on one rank) and atomic; readers validate.

#include "common/h5/provenance.hpp"
#include "probe/config.hpp"
#include "probe/fork.hpp"
#include "probe/stiffness.hpp"

#include <array>
#include <cstdint>
#include <string>

namespace aniso::probe {

inline constexpr std::int64_t probe_schema_version = 1;

/// The checkpoint a probe came from.
struct ProbeSource {
  std::string path;                ///< as given on the command line
  std::string hash;                ///< h5::content_hash of the file
  double strain = 0;               ///< loading strain, -eps_11 of the cell (compression positive)
  Vec3 cell_strain = Vec3::Zero(); ///< engineering strain of the cell per axis, extension positive
};

/// The settings that must agree between forks that are collected together.
struct ForkSettings {
  double increment = 0;
  double inertial_number = 0;
  std::int64_t hold_steps = 0;
  std::int64_t window_steps = 0;
};
ForkSettings fork_settings(const ProbeConfig& config);
bool operator==(const ForkSettings& a, const ForkSettings& b);

struct ForkFile {
  ProbeSource source;
  ForkSettings settings;
  ForkResult result;
};

struct ProbeResult {
  ProbeSource source;
  ForkSettings settings;
  Stiffness stiffness;
  Mat3 stress_reference = Mat3::Zero(); ///< the reference fork's final reading [Pa]
  bool checks_passed = false;           ///< both increment checks passed
  std::array<ForkResult, n_fork_files> forks;
};

/// Stem of a checkpoint path: "runs/demo/load_003.h5" -> "load_003".
std::string checkpoint_stem(const std::string& checkpoint_path);
/// <folder>/probe_<stem>_fork<N>.h5
std::string fork_path(const std::string& folder, const std::string& checkpoint_path, int index);
/// <folder>/probe_<stem>.h5 (the CSV has the same name with .csv)
std::string result_path(const std::string& folder, const std::string& checkpoint_path);

void write_fork_file(const std::string& path, const ForkFile& fork, const h5::Provenance& provenance);
ForkFile read_fork_file(const std::string& path);

void write_probe_result(const std::string& path, const ProbeResult& result, const h5::Provenance& provenance);
ProbeResult read_probe_result(const std::string& path);
/// One header line and one row: source, strain, K_C and every entry of C, D, Q_plus, Q_minus.
void write_probe_csv(const std::string& path, const ProbeResult& result);

} // namespace aniso::probe
