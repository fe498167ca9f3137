#pragma once
// Velocity Verlet for the fluctuating motion in a deforming periodic cell, and
// the Rayleigh time-step criterion checked before a run starts.

#include "common/cell.hpp"
#include "dem/contact_law.hpp"
#include "dem/particles.hpp"

namespace aniso::dem {

/// v += F/m * dt, omega += T/I * dt (spheres; the inertia is isotropic).
void kick(Particles& particles, double dt);

/// Moves particles by their fluctuating velocity, then strains the cell by
/// `strain_rate` over dt and maps every position affinely with it; wraps into the cell.
void drift(Particles& particles, PeriodicCell& cell, const Vec3& strain_rate, double dt);

/// Rayleigh critical step of the smallest particle [s].
double critical_time_step(const Particles& particles, double density, const ContactMaterial& material);

/// Checks a requested step against the critical one; throws NumericalError naming both if above.
void require_stable_time_step(double time_step, double critical);

} // namespace aniso::dem
