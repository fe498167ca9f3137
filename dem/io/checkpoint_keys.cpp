#include "dem/io/checkpoint_keys.hpp"

#include "common/error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace aniso::dem::io {
namespace {

std::string with_space(const char* unit) {
  return *unit ? std::string(" ") + unit : std::string();
}

class Adopter {
public:
  Adopter(config::Reader& reader, std::string path) : reader_(reader), path_(std::move(path)) {}

  // The configured value must equal the stored one to 1e-9 when given; either way the stored one is used.
  void real(const char* key, double& configured, double stored, const char* unit) {
    if (reader_.given(key) && !(std::abs(configured - stored) <= 1e-9 * std::abs(stored)))
      mismatches_ += fmt::format("\n  {} = {:g}{}, the checkpoint has {:g}{}", key, configured,
                                 with_space(unit), stored, with_space(unit));
    configured = stored;
    reader_.replace(key, fmt::format("{}", stored), "from the input checkpoint");
  }
  // A size bound is kept when every stored diameter lies within it.
  void bound(const char* key, double& configured, double stored_extreme, bool is_min) {
    const bool inside =
        is_min ? stored_extreme >= configured * (1 - 1e-9) : stored_extreme <= configured * (1 + 1e-9);
    if (reader_.given(key) && !inside)
      mismatches_ += fmt::format("\n  {} = {:g} m, the checkpoint's diameters reach {:g} m", key, configured,
                                 stored_extreme);
    configured = stored_extreme;
    reader_.replace(key, fmt::format("{}", stored_extreme),
                    "from the input checkpoint (its extreme diameter)");
  }
  void count(const char* key, std::int64_t& configured, std::int64_t stored) {
    if (reader_.given(key) && configured != stored)
      mismatches_ += fmt::format("\n  {} = {}, the checkpoint has {} particles", key, configured, stored);
    configured = stored;
    reader_.replace(key, std::to_string(stored), "from the input checkpoint");
  }
  void finish() const {
    require_input(
        mismatches_.empty(),
        fmt::format("the configuration gives keys that the input checkpoint '{}' fixes (its particles "
                    "and their material), with other values:{}\nA run from a checkpoint uses the "
                    "file's values: remove these keys, or prepare a new assembly with them",
                    path_, mismatches_));
  }

private:
  config::Reader& reader_;
  std::string path_;
  std::string mismatches_;
};

double stored(const h5::Checkpoint& checkpoint, const char* name, const std::string& path) {
  return h5::parameter(checkpoint, name, path);
}

} // namespace

void adopt_checkpoint_values(DemConfig& config, config::Reader& reader, const h5::Checkpoint& checkpoint,
                             const std::string& path) {
  Adopter adopt(reader, path);
  const auto& rows = checkpoint.particles;
  adopt.count("dem.particles.count", config.particles.count, static_cast<std::int64_t>(rows.size()));
  const auto [smallest, largest] = std::minmax_element(rows.diameter.begin(), rows.diameter.end());
  adopt.bound("dem.particles.diameter_min", config.particles.diameter_min, *smallest, true);
  adopt.bound("dem.particles.diameter_max", config.particles.diameter_max, *largest, false);
  adopt.real("dem.particles.d50", config.particles.d50, stored(checkpoint, "d50", path), "m");
  adopt.real("dem.particles.density", config.particles.density, stored(checkpoint, "density", path),
             "kg/m^3");
  // One aspect ratio for every particle is what prepare makes; a mixed file has no single value.
  const auto [flattest, roundest] = std::minmax_element(rows.aspect_ratio.begin(), rows.aspect_ratio.end());
  if (*flattest == *roundest)
    adopt.real("dem.particles.aspect_ratio", config.particles.aspect_ratio, *flattest, "");
  if (h5::has_parameter(checkpoint, "ovoid_splice_angle")) {
    double degrees = config.particles.splice_angle * 180.0 / std::numbers::pi;
    adopt.real("dem.particles.splice_angle_degrees", degrees,
               stored(checkpoint, "ovoid_splice_angle", path) * 180.0 / std::numbers::pi, "degrees");
    config.particles.splice_angle = degrees * std::numbers::pi / 180.0;
  }
  adopt.real("dem.material.shear_modulus", config.material.shear_modulus,
             stored(checkpoint, "shear_modulus", path), "Pa");
  adopt.real("dem.material.poisson_ratio", config.material.poisson_ratio,
             stored(checkpoint, "poisson_ratio", path), "");
  adopt.real("dem.integration.explosion_overlap", config.integration.explosion_overlap,
             stored(checkpoint, "explosion_overlap", path), "");
  adopt.real("dem.integration.skin", config.integration.skin,
             stored(checkpoint, "skin", path) / stored(checkpoint, "d50", path), "D50");
  adopt.finish();
}

} // namespace aniso::dem::io
