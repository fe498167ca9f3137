#pragma once
// Hertz normal force and Mindlin tangential stiffness with a Coulomb limit
// (paper section 2: "Hertz-Mindlin interactions ... no contact bonding or
// rotational resistance"), plus optional viscous contact damping. Stateless
// functions: the only memory, the elastic tangential force, is passed in and updated.
// Formulas and references: docs/methods/dem-contact-law.md.

#include "common/tensor.hpp"

namespace aniso::dem::model {

/// Elastic and frictional constants shared by all particles (one material).
struct ContactMaterial {
  double shear_modulus = 29e9; ///< G [Pa]
  double poisson_ratio = 0.15; ///< nu
  double friction = 0.5;       ///< Coulomb coefficient mu
  double damping_ratio = 0.0;  ///< viscous contact damping as a fraction of critical, normal and tangential
};

/// Geometry and inertia of one pair that do not change during the contact.
struct PairProperties {
  double effective_radius = 0; ///< R* = R_i R_j / (R_i + R_j) [m] (or from principal curvatures, ovoids)
  double effective_mass = 0;   ///< m* = m_i m_j / (m_i + m_j) [kg]
};

/// What the narrow phase and the integrator know about the contact this step.
struct ContactKinematics {
  Vec3 normal;            ///< unit normal pointing from particle i to particle j
  double overlap = 0;     ///< > 0 when touching [m]
  Vec3 relative_velocity; ///< velocity of j's surface relative to i's at the contact point [m/s]
  double time_step = 0;   ///< [s]
};

/// The history of one contact: the elastic tangential force and whether it slides.
struct ContactHistory {
  Vec3 tangential_force = Vec3::Zero(); ///< elastic tangential force on i, built incrementally [N]
  bool sliding = false;
  /// Last contact normal of a pair with an ovoid (zero: none), where its narrow phase starts:
  /// part of the contact's state so that restarts and any rank count start from the same normal.
  Vec3 normal = Vec3::Zero();
};

struct ContactForce {
  Vec3 force_on_i = Vec3::Zero();  ///< total force on i from j (j receives the opposite) [N]
  double normal_force = 0;         ///< elastic normal force magnitude, > 0 is compressive [N]
  double normal_stiffness = 0;     ///< dF_n / d overlap [N/m]
  double tangential_stiffness = 0; ///< Mindlin no-slip stiffness [N/m]
};

/// E* = E / (2 (1 - nu^2)) = G / (1 - nu) for two particles of one material.
double contact_modulus(const ContactMaterial& material);
/// Hertz normal force (4/3) E* sqrt(R*) overlap^(3/2).
double hertz_normal_force(double contact_modulus, double effective_radius, double overlap);
/// Hertz normal stiffness 2 E* sqrt(R* overlap).
double hertz_normal_stiffness(double contact_modulus, double effective_radius, double overlap);
/// Mindlin no-slip tangential stiffness 8 G* a with G* = G / (2 (2 - nu)) and a = sqrt(R* overlap).
double mindlin_tangential_stiffness(const ContactMaterial& material, double effective_radius, double overlap);
/// Rayleigh critical time step of a particle of radius R: pi R sqrt(rho/G) / (0.1631 nu + 0.8766).
double rayleigh_time_step(double radius, double density, const ContactMaterial& material);
/// Duration of an undamped Hertzian impact at approach speed v (Johnson 1985, eq. 11.24).
double hertz_contact_duration(double contact_modulus, double effective_radius, double effective_mass,
                              double approach_speed);

/// Material constants derived once per force pass instead of once per contact.
struct ContactConstants {
  double e_star = 0;   ///< E* = G / (1 - nu) [Pa]
  double g_star = 0;   ///< G* = G / (2 (2 - nu)) [Pa]
  double friction = 0; ///< mu
  double damping_ratio = 0;
};
ContactConstants contact_constants(const ContactMaterial& material);

/// Hertz normal force and stiffness and the Mindlin no-slip stiffness at one overlap, from one
/// square root (the contact radius a = sqrt(R* delta)): F_n = (4/3) E* a delta, k_n = 2 E* a,
/// k_t = 8 G* a. The force law and a restart's rebuilt contact records share this evaluation.
struct HertzMindlinSprings {
  double normal_force = 0;         ///< [N]
  double normal_stiffness = 0;     ///< [N/m]
  double tangential_stiffness = 0; ///< [N/m]
};
HertzMindlinSprings hertz_mindlin_springs(const ContactConstants& constants, double effective_radius,
                                          double overlap);

/// The same force with the constants precomputed (the inner loop's form).
ContactForce hertz_mindlin_force(const ContactConstants& constants, const PairProperties& pair,
                                 const ContactKinematics& kinematics, ContactHistory& history);

/// Force of one time step; rotates the tangential force into the current tangent plane,
/// adds this step's tangential motion and caps it at the Coulomb limit.
ContactForce hertz_mindlin_force(const ContactMaterial& material, const PairProperties& pair,
                                 const ContactKinematics& kinematics, ContactHistory& history);

} // namespace aniso::dem::model
