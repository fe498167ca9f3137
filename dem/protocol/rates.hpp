#pragma once
// The limits a protocol's loading rate is held to: quasi-static, and finite.

#include <string>

namespace aniso::dem::protocol {

/// InputError unless a strain at this rate and time step ends within max_run_steps steps: a
/// stress or inertial number many orders too small (1e-300 Pa) would otherwise run forever.
void require_reachable_strain(double strain, double rate, double time_step, const std::string& what);

/// Above this inertial number a loading is not quasi-static (dense flow, GDR MiDi 2004); the
/// rate chart (docs/methods/dem.md) shows q/p converged at I <= 1e-3 and drifting above.
inline constexpr double quasi_static_inertial_number = 1e-2;

/// Time steps beyond which a run counts as never ending: 25 days at 6400 particles and
/// 3e6 particle-steps/s; the paper's loading takes about 3e6.
inline constexpr double max_run_steps = 1e9;

} // namespace aniso::dem::protocol
