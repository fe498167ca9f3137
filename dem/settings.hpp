#pragma once
// Simulation settings and rates derived from the configuration.

#include "dem/config.hpp"
#include "dem/simulation.hpp"

namespace aniso::dem {

/// Material, shape, time step (from the Rayleigh step of the smallest particle's half-height),
/// skin, servo.
SimulationSettings settings_from_config(const DemConfig& config, double smallest_diameter);

/// Strain rate for an inertial number at a mean stress: rate = I / (D50 sqrt(rho / p)).
double strain_rate_for_inertial_number(double inertial_number, double d50, double density,
                                       double mean_stress);

} // namespace aniso::dem
