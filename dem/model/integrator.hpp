#pragma once
// Velocity Verlet for the fluctuating motion in a deforming periodic cell, and
// the Rayleigh time-step criterion checked before a run starts.

#include "common/cell.hpp"
#include "common/exact_sum.hpp"
#include "dem/data/particles.hpp"
#include "dem/model/contact_law.hpp"

namespace aniso::dem::model {

/// v += F/m * dt, omega += I_world^-1 T * dt (the inertia is isotropic for spheres and
/// axisymmetric for ovoids, so I_world^-1 needs only the particle axis).
void kick(data::Particles& particles, double dt);

/// I_world^-1 v of particle k: v / I for a sphere, the axisymmetric inverse for an ovoid.
Vec3 inverse_inertia_world_times(const data::Particles& particles, std::size_t k, const Vec3& v);

/// This rank's sums for the minimiser (protocol/fire.hpp), over its owned particles, in
/// mass-weighted coordinates u = sqrt(M) v, f = F / sqrt(M): the power F.v + T.omega [W], |u|^2 =
/// m v.v + omega.I omega [J] and |f|^2 = F.F / m + T.I^-1 T [N^2/kg], each exact.
struct MotionSums {
  ExactSum power, speed_squared, force_squared;
};
MotionSums motion_sums(const data::Particles& particles);

/// The minimiser's steering (protocol/fire.hpp): every owned particle's fluctuating velocity
/// becomes keep v + toward F/m and its angular velocity keep omega + toward I^-1 T.
void steer_velocities(data::Particles& particles, double keep, double toward);

/// Global viscous damping of the fluctuating motion: multiplies every owned particle's
/// fluctuating velocity by `factor` = exp(-gamma h) and the angular velocity by `spin_factor`
/// (exp(-f gamma h) for a spin rate f times gamma), the exact decay over h of
/// dv/dt = -gamma v. Acting on the fluctuating velocity only, it leaves the affine field of
/// the deforming cell undamped (Kuhn's OVAL practice, shared/reference/ovoid.md).
void damp_velocities(data::Particles& particles, double factor, double spin_factor);

/// Moves particles by their fluctuating velocity, then strains the cell by
/// `strain_rate` over dt and maps every position affinely with it; wraps into the cell.
/// Ovoids also turn by their exact torque-free rotation over dt; a sphere's orientation
/// carries no information and is left as it is.
void drift(data::Particles& particles, PeriodicCell& cell, const Vec3& strain_rate, double dt);

/// Rayleigh critical step of the smallest particle [s], taken over its smallest half-extent
/// (the half-height alpha a of an ovoid) so that flat particles get a safe step.
double critical_time_step(const data::Particles& particles, double density, const ContactMaterial& material);

/// Checks a requested step against the critical one; throws NumericalError naming both if above.
void require_stable_time_step(double time_step, double critical);

} // namespace aniso::dem::model
