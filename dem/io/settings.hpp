#pragma once
// Simulation settings and rates derived from the configuration.

#include "dem/config.hpp"
#include "dem/simulation.hpp"

#include <string>

namespace aniso::dem::io {

/// Material, shape, time step (from the Rayleigh step of the smallest particle's half-height),
/// skin, servo.
SimulationSettings settings_from_config(const DemConfig& config, double smallest_diameter);

/// Strain rate for an inertial number at a mean stress: rate = I / (D50 sqrt(rho / p)).
double strain_rate_for_inertial_number(double inertial_number, double d50, double density,
                                       double mean_stress);

/// InputError unless a strain at this rate and time step ends within max_run_steps steps: a
/// stress or inertial number many orders too small (1e-300 Pa) would otherwise run forever.
void require_reachable_strain(double strain, double rate, double time_step, const std::string& what);

/// Above this inertial number a loading is not quasi-static (dense flow, GDR MiDi 2004); the
/// rate chart (docs/methods/dem.md) shows q/p converged at I <= 1e-3 and drifting above.
inline constexpr double quasi_static_inertial_number = 1e-2;

/// Time steps beyond which a run counts as never ending: 25 days at 6400 particles and
/// 3e6 particle-steps/s; the paper's loading takes about 3e6.
inline constexpr double max_run_steps = 1e9;

} // namespace aniso::dem::io
