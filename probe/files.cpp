#include "probe/files.hpp"

#include "common/error.hpp"
#include "common/h5/atomic_write.hpp"
#include "common/h5/file.hpp"
#include "common/output_folder.hpp"
#include "common/units.hpp"
#include "probe/h5_values.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>

namespace aniso::probe {
namespace {

constexpr const char* fork_schema = "aniso-probe-fork";
constexpr const char* result_schema = "aniso-probe";

void write_schema(h5::File& file, const char* schema) {
  file.write_attribute("schema", std::string_view(schema));
  file.write_attribute("schema_version", probe_schema_version);
}

void check_schema(const h5::File& file, const char* schema) {
  const std::string found = file.read_string_attribute("schema");
  if (found != schema) file.fail(fmt::format("schema '{}' found, expected '{}'", found, schema));
  const auto version = file.read_attribute<std::int64_t>("schema_version");
  if (version != probe_schema_version)
    file.fail(fmt::format("schema_version {} found, expected {}", version, probe_schema_version));
}

void write_source(h5::Group& group, const ProbeSource& source, const ForkSettings& settings) {
  group.write_attribute("source", std::string_view(source.path));
  group.write_attribute("source_hash", std::string_view(source.hash));
  group.write_attribute_with_units("strain", source.strain, units::none);
  write_vector(group, "cell_strain", source.cell_strain, units::none,
               "engineering strain of the checkpoint's cell per axis, extension positive");
  group.write_attribute_with_units("increment", settings.increment, units::none);
  group.write_attribute_with_units("inertial_number", settings.inertial_number, units::none);
  group.write_attribute("hold_steps", settings.hold_steps);
  group.write_attribute("window_steps", settings.window_steps);
}

void read_source(const h5::Group& group, ProbeSource& source, ForkSettings& settings) {
  source.path = group.read_string_attribute("source");
  source.hash = group.read_string_attribute("source_hash");
  source.strain = read_finite(group, "strain");
  source.cell_strain = read_vector(group, "cell_strain");
  settings.increment = read_finite(group, "increment");
  settings.inertial_number = read_finite(group, "inertial_number");
  settings.hold_steps = group.read_attribute<std::int64_t>("hold_steps");
  settings.window_steps = group.read_attribute<std::int64_t>("window_steps");
  if (!(settings.increment > 0)) group.fail("attribute 'increment' must be positive");
}

void write_samples(h5::Group& group, const std::string& name, const std::vector<Mat3>& samples,
                   std::string_view description) {
  std::vector<double> rows;
  for (const Mat3& m : samples)
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        rows.push_back(m(i, j));
  group.write_dataset<double>(name, rows, {samples.size(), 3, 3}, units::pascal, description);
}

std::vector<Mat3> read_samples(const h5::Group& group, const std::string& name) {
  const h5::Dims dims = group.open_dataset(name).dims();
  if (dims.size() != 3 || dims[0] == 0 || dims[1] != 3 || dims[2] != 3)
    group.fail(fmt::format("dataset '{}' has dims {}, expected [n > 0, 3, 3]", name, h5::format_dims(dims)));
  const std::vector<double> rows = group.read_dataset<double>(name, dims);
  std::vector<Mat3> samples(dims[0]);
  for (std::size_t k = 0; k < samples.size(); ++k) {
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        const double v = rows[9 * k + static_cast<std::size_t>(3 * i + j)];
        if (!std::isfinite(v)) group.fail("'" + name + "' holds a non-finite value");
        samples[k](i, j) = v;
      }
    }
  }
  return samples;
}

void write_fork_group(h5::Group& group, const ForkResult& fork) {
  const ForkSpec spec = fork_spec(fork.index);
  group.write_attribute("index", std::int64_t{fork.index});
  group.write_attribute("axis", std::int64_t{spec.sign == 0 ? 0 : spec.axis + 1});
  group.write_attribute("sign", std::int64_t{spec.sign});
  group.write_attribute_with_units("strain_rate", fork.strain_rate, units::per_second);
  group.write_attribute_with_units("time_step", fork.time_step, units::second);
  group.write_attribute("half_steps", fork.half_steps);
  group.write_attribute("hold_steps", fork.hold_steps);
  group.write_attribute("contacts_start", fork.contacts_start);
  group.write_attribute("sliding_start", fork.sliding_start);
  group.write_attribute("contacts_final", fork.contacts_final);
  group.write_attribute("sliding_final", fork.sliding_final);
  write_matrix(group, "stress_start", fork.stress_start, units::pascal,
               "restored stress of the checkpoint, tension positive");
  write_samples(group, "samples_half", fork.samples_half,
                "stress at each control update of the reading window after the first half");
  write_samples(group, "samples_final", fork.samples_final,
                "stress at each control update of the reading window after the whole increment");
  write_vector(group, "strain_half", fork.strain_half, units::none,
               "ln(L / L_start) per axis after half the increment");
  write_vector(group, "strain_final", fork.strain_final, units::none,
               "ln(L / L_start) per axis after the whole increment");
}

ForkResult read_fork_group(const h5::Group& group) {
  ForkResult fork;
  const auto index = group.read_attribute<std::int64_t>("index");
  if (index < reference_fork || index > n_forks)
    group.fail(fmt::format("fork index {} is not in {}..{}", index, reference_fork, n_forks));
  fork.index = static_cast<int>(index);
  fork.strain_rate = read_finite(group, "strain_rate");
  fork.time_step = read_finite(group, "time_step");
  fork.half_steps = group.read_attribute<std::int64_t>("half_steps");
  fork.hold_steps = group.read_attribute<std::int64_t>("hold_steps");
  fork.contacts_start = group.read_attribute<std::int64_t>("contacts_start");
  fork.sliding_start = group.read_attribute<std::int64_t>("sliding_start");
  fork.contacts_final = group.read_attribute<std::int64_t>("contacts_final");
  fork.sliding_final = group.read_attribute<std::int64_t>("sliding_final");
  fork.stress_start = read_matrix(group, "stress_start");
  fork.samples_half = read_samples(group, "samples_half");
  fork.samples_final = read_samples(group, "samples_final");
  fork.strain_half = read_vector(group, "strain_half");
  fork.strain_final = read_vector(group, "strain_final");
  return fork;
}

// Writes the file through `body` at a temporary name and renames it into place.
template <class Body> void write_atomically(const std::string& path, const Body& body) {
  const std::string folder = std::filesystem::path(path).parent_path().string();
  create_output_folder(folder);
  h5::AtomicFile atomic(path);
  {
    h5::File file = h5::File::create(atomic.temp_path());
    body(file);
    file.close();
  }
  atomic.commit();
}

} // namespace

ForkSettings fork_settings(const ProbeConfig& config) {
  return {config.increment, config.inertial_number, config.hold_steps, config.window_steps};
}

bool operator==(const ForkSettings& a, const ForkSettings& b) {
  return a.increment == b.increment && a.inertial_number == b.inertial_number &&
         a.hold_steps == b.hold_steps && a.window_steps == b.window_steps;
}

std::string checkpoint_stem(const std::string& checkpoint_path) {
  return std::filesystem::path(checkpoint_path).stem().string();
}

std::string fork_path(const std::string& folder, const std::string& checkpoint_path, int index) {
  return (std::filesystem::path(folder) /
          fmt::format("probe_{}_fork{}.h5", checkpoint_stem(checkpoint_path), index))
      .string();
}

std::string result_path(const std::string& folder, const std::string& checkpoint_path) {
  return (std::filesystem::path(folder) / fmt::format("probe_{}.h5", checkpoint_stem(checkpoint_path)))
      .string();
}

void write_fork_file(const std::string& path, const ForkFile& fork, const h5::Provenance& provenance) {
  write_atomically(path, [&](h5::File& file) {
    write_schema(file, fork_schema);
    h5::Group group = file.create_group("fork");
    write_source(group, fork.source, fork.settings);
    write_fork_group(group, fork.result);
    h5::write_provenance(file, provenance);
  });
}

ForkFile read_fork_file(const std::string& path) {
  const h5::File file = h5::File::open(path);
  check_schema(file, fork_schema);
  const h5::Group group = file.open_group("fork");
  ForkFile fork;
  read_source(group, fork.source, fork.settings);
  fork.result = read_fork_group(group);
  return fork;
}

void write_probe_result(const std::string& path, const ProbeResult& result,
                        const h5::Provenance& provenance) {
  const Stiffness& s = result.stiffness;
  write_atomically(path, [&](h5::File& file) {
    write_schema(file, result_schema);
    h5::Group group = file.create_group("stiffness");
    write_source(group, result.source, result.settings);
    group.write_attribute_with_units("K_C", s.K_C, units::pascal);
    group.write_attribute("checks_passed", std::int64_t{result.checks_passed ? 1 : 0});
    write_matrix(group, "Q_plus", s.Q_plus, units::pascal,
                 "(i, j) = d sigma_ii / d eps_jj of the extension fork on x_j, eq. (Oplus)");
    write_matrix(group, "Q_minus", s.Q_minus, units::pascal,
                 "(i, j) = d sigma_ii / d eps_jj of the compression fork on x_j, eq. (Ominus)");
    write_matrix(group, "C", s.C, units::pascal, "incrementally linear stiffness (Q+ + Q-)/2, eq. (decomp)");
    write_matrix(group, "D", s.D, units::pascal,
                 "incrementally non-linear stiffness (Q+ - Q-)/2, eq. (decomp)");
    write_vector(group, "O_plus", s.O_plus, units::pascal, "O_i^+ = d sigma_ii / d eps_ii, extension forks");
    write_vector(group, "O_minus", s.O_minus, units::pascal,
                 "O_i^- = d sigma_ii / d eps_ii, compression forks");
    write_matrix(group, "K_plus", s.K_plus, units::none, "(j, i) = K_i^{j+} = d sigma_jj / d sigma_ii");
    write_matrix(group, "K_minus", s.K_minus, units::none, "(j, i) = K_i^{j-} = d sigma_jj / d sigma_ii");
    write_matrix(group, "stress_reference", result.stress_reference, units::pascal,
                 "the reference fork's final reading, tension positive");
    write_vector(group, "linearity_plus", s.linearity_plus, units::none,
                 "|M_second - M_first| / O_i^+ of the two half increments");
    write_vector(group, "linearity_minus", s.linearity_minus, units::none,
                 "|M_second - M_first| / O_i^- of the two half increments");
    write_vector(group, "noise_plus", s.noise_plus, units::none,
                 "rms of d sigma_ii over the reading window / |d sigma_ii|, extension forks");
    write_vector(group, "noise_minus", s.noise_minus, units::none,
                 "rms of d sigma_ii over the reading window / |d sigma_ii|, compression forks");
    write_vector(group, "sliding_plus", s.sliding_plus, units::none,
                 "(sliding contacts of the fork - of the reference) / contacts, extension forks");
    write_vector(group, "sliding_minus", s.sliding_minus, units::none,
                 "(sliding contacts of the fork - of the reference) / contacts, compression forks");
    write_vector(group, "resolution_plus", s.resolution_plus, units::none,
                 "|d sigma_ii| / largest |sigma_kl| of the reference, extension forks");
    write_vector(group, "resolution_minus", s.resolution_minus, units::none,
                 "|d sigma_ii| / largest |sigma_kl| of the reference, compression forks");
    h5::Group forks = file.create_group("forks");
    for (const ForkResult& fork : result.forks) {
      h5::Group child = forks.create_group(fmt::format("fork_{}", fork.index));
      write_fork_group(child, fork);
    }
    h5::write_provenance(file, provenance);
  });
}

ProbeResult read_probe_result(const std::string& path) {
  const h5::File file = h5::File::open(path);
  check_schema(file, result_schema);
  const h5::Group group = file.open_group("stiffness");
  ProbeResult r;
  read_source(group, r.source, r.settings);
  Stiffness& s = r.stiffness;
  s.K_C = read_finite(group, "K_C");
  r.checks_passed = group.read_attribute<std::int64_t>("checks_passed") != 0;
  s.Q_plus = read_matrix(group, "Q_plus");
  s.Q_minus = read_matrix(group, "Q_minus");
  s.C = read_matrix(group, "C");
  s.D = read_matrix(group, "D");
  s.O_plus = read_vector(group, "O_plus");
  s.O_minus = read_vector(group, "O_minus");
  s.K_plus = read_matrix(group, "K_plus");
  s.K_minus = read_matrix(group, "K_minus");
  r.stress_reference = read_matrix(group, "stress_reference");
  s.linearity_plus = read_vector(group, "linearity_plus");
  s.linearity_minus = read_vector(group, "linearity_minus");
  s.noise_plus = read_vector(group, "noise_plus");
  s.noise_minus = read_vector(group, "noise_minus");
  s.sliding_plus = read_vector(group, "sliding_plus");
  s.sliding_minus = read_vector(group, "sliding_minus");
  s.resolution_plus = read_vector(group, "resolution_plus");
  s.resolution_minus = read_vector(group, "resolution_minus");
  const h5::Group forks = file.open_group("forks");
  for (int k = 0; k < n_fork_files; ++k) {
    r.forks[static_cast<std::size_t>(k)] = read_fork_group(forks.open_group(fmt::format("fork_{}", k)));
    if (r.forks[static_cast<std::size_t>(k)].index != k)
      forks.fail(fmt::format("fork_{} holds another fork", k));
  }
  const double mean = s.C.sum() / 9.0;
  if (std::abs(mean - s.K_C) > 1e-12 * std::abs(mean))
    group.fail(fmt::format("K_C = {:.6g} Pa is not the mean of C's entries ({:.6g} Pa)", s.K_C, mean));
  return r;
}

void write_probe_csv(const std::string& path, const ProbeResult& result) {
  const Stiffness& s = result.stiffness;
  std::string header = "source,source_hash,strain,increment,K_C";
  std::string row = fmt::format("{},{},{:.17g},{:.17g},{:.17g}", result.source.path, result.source.hash,
                                result.source.strain, result.settings.increment, s.K_C);
  const std::pair<const char*, const Mat3*> matrices[] = {
      {"C", &s.C}, {"D", &s.D}, {"Q_plus", &s.Q_plus}, {"Q_minus", &s.Q_minus}};
  for (const auto& [name, matrix] : matrices) {
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        header += fmt::format(",{}_{}{}", name, i + 1, j + 1);
        row += fmt::format(",{:.17g}", (*matrix)(i, j));
      }
    }
  }
  header += ",checks_passed";
  row += result.checks_passed ? ",1" : ",0";
  h5::write_text_atomically(path, header + '\n' + row + '\n');
}

} // namespace aniso::probe
