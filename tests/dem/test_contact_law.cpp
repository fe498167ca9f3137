// Tests of the Hertz-Mindlin contact law (dem/model/contact_law.hpp) with the
// paper's material: G = 29 GPa, nu = 0.15, mu = 0.5, rho = 2650 kg/m^3 and
// particle diameters 0.075-0.28 mm.
#include "dem/model/contact_law.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

namespace {

using aniso::Vec3;
using namespace aniso::dem;
using namespace aniso::dem::model;

constexpr double kDensity = 2650.0;
constexpr double kSmallDiameter = 0.075e-3;
constexpr double kLargeDiameter = 0.28e-3;

ContactMaterial paper_material(double damping_ratio = 0.0) {
  ContactMaterial material;
  material.shear_modulus = 29e9;
  material.poisson_ratio = 0.15;
  material.friction = 0.5;
  material.damping_ratio = damping_ratio;
  return material;
}

double sphere_mass(double radius) {
  return kDensity * 4.0 / 3.0 * std::numbers::pi * radius * radius * radius;
}

PairProperties pair_of(double radius_i, double radius_j) {
  PairProperties pair;
  pair.effective_radius = radius_i * radius_j / (radius_i + radius_j);
  const double m_i = sphere_mass(radius_i);
  const double m_j = sphere_mass(radius_j);
  pair.effective_mass = m_i * m_j / (m_i + m_j);
  return pair;
}

PairProperties paper_pair() {
  return pair_of(0.5 * kSmallDiameter, 0.5 * kLargeDiameter);
}

double relative_error(double value, double reference) {
  return std::abs(value - reference) / std::abs(reference);
}

TEST(ContactLaw, ContactModulusOfOneMaterial) {
  const ContactMaterial material = paper_material();
  const double nu = material.poisson_ratio;
  const double young = 2.0 * material.shear_modulus * (1.0 + nu);
  EXPECT_LT(relative_error(contact_modulus(material), young / (2.0 * (1.0 - nu * nu))), 1e-14);
  EXPECT_LT(relative_error(contact_modulus(material), 29e9 / 0.85), 1e-14);
}

// 1. Hertz force and stiffness against the closed forms, and k_n = dF_n/d delta.
TEST(ContactLaw, HertzForceAndStiffnessMatchAnalyticFormula) {
  const ContactMaterial material = paper_material();
  const PairProperties pair = paper_pair();
  const double e_star = contact_modulus(material);
  const double r_star = pair.effective_radius;
  const double g_star = material.shear_modulus / (2.0 * (2.0 - material.poisson_ratio));
  for (const double overlap : {1e-10, 1e-9, 3e-9, 1e-8, 1e-7, 1e-6}) {
    SCOPED_TRACE(overlap);
    const double force = (4.0 / 3.0) * e_star * std::sqrt(r_star) * std::pow(overlap, 1.5);
    const double stiffness = 2.0 * e_star * std::sqrt(r_star * overlap);
    const double tangential = 8.0 * g_star * std::sqrt(r_star * overlap);
    EXPECT_LT(relative_error(hertz_normal_force(e_star, r_star, overlap), force), 1e-12);
    EXPECT_LT(relative_error(hertz_normal_stiffness(e_star, r_star, overlap), stiffness), 1e-12);
    EXPECT_LT(relative_error(mindlin_tangential_stiffness(material, r_star, overlap), tangential), 1e-12);

    const double h = 1e-4 * overlap;
    const double difference =
        (hertz_normal_force(e_star, r_star, overlap + h) - hertz_normal_force(e_star, r_star, overlap - h)) /
        (2.0 * h);
    EXPECT_LT(relative_error(difference, stiffness), 1e-6);

    // The combined step function reports the same values.
    ContactHistory history;
    const ContactKinematics kinematics{Vec3::UnitX(), overlap, Vec3::Zero(), 1e-9};
    const ContactForce result = hertz_mindlin_force(material, pair, kinematics, history);
    EXPECT_LT(relative_error(result.normal_force, force), 1e-12);
    EXPECT_LT(relative_error(result.normal_stiffness, stiffness), 1e-12);
    EXPECT_LT(relative_error(result.tangential_stiffness, tangential), 1e-12);
    EXPECT_LT(relative_error(result.force_on_i.x(), -force), 1e-12); // pushes i away from j
    EXPECT_EQ(result.force_on_i.y(), 0.0);
    EXPECT_EQ(result.force_on_i.z(), 0.0);
  }
  EXPECT_EQ(hertz_normal_force(e_star, r_star, 0.0), 0.0);
  EXPECT_EQ(hertz_normal_force(e_star, r_star, -1e-9), 0.0);
  EXPECT_EQ(hertz_normal_stiffness(e_star, r_star, -1e-9), 0.0);
  EXPECT_EQ(mindlin_tangential_stiffness(material, r_star, -1e-9), 0.0);
}

TEST(ContactLaw, ContactDurationConstantFromEnergyIntegral) {
  // t_c = 2 (delta_max / v) (2/5) B(2/5, 1/2), delta_max = (15 m* v^2 / (16 E* sqrt(R*)))^(2/5).
  const ContactMaterial material = paper_material();
  const PairProperties pair = paper_pair();
  const double e_star = contact_modulus(material);
  const double beta = std::tgamma(0.4) * std::tgamma(0.5) / std::tgamma(0.9);
  for (const double speed : {1e-3, 0.1, 2.0}) {
    const double delta_max = std::pow(
        15.0 * pair.effective_mass * speed * speed / (16.0 * e_star * std::sqrt(pair.effective_radius)), 0.4);
    const double expected = 2.0 * delta_max / speed * 0.4 * beta;
    const double duration = hertz_contact_duration(e_star, pair.effective_radius, pair.effective_mass, speed);
    EXPECT_LT(relative_error(duration, expected), 1e-12);
    // Johnson (1985) eq. 11.24 quotes the constant rounded to 2.87.
    const double johnson = 2.87 * std::pow(pair.effective_mass * pair.effective_mass /
                                               (pair.effective_radius * e_star * e_star * speed),
                                           0.2);
    EXPECT_LT(relative_error(duration, johnson), 1e-3);
  }
}

// A head-on impact of two spheres on the x axis (i at the left, j at the
// right), integrated with velocity Verlet through this contact law.
struct Impact {
  double duration = 0;    // time with positive overlap, crossings interpolated linearly
  double restitution = 0; // separation speed / approach speed
  double expected_duration = 0;
};

Impact simulate_impact(double damping_ratio, double radius_i, double radius_j, double approach_speed) {
  const ContactMaterial material = paper_material(damping_ratio);
  const PairProperties pair = pair_of(radius_i, radius_j);
  const double m_i = sphere_mass(radius_i);
  const double m_j = sphere_mass(radius_j);
  Impact impact;
  impact.expected_duration = hertz_contact_duration(contact_modulus(material), pair.effective_radius,
                                                    pair.effective_mass, approach_speed);
  const double dt = impact.expected_duration / 200.0;

  // Touching at t = 0, j moving towards i.
  double x_i = 0.0, x_j = radius_i + radius_j;
  double v_i = 0.0, v_j = -approach_speed;
  ContactHistory history;
  const auto force_on_i = [&](double vi, double vj) {
    const ContactKinematics kinematics{Vec3::UnitX(), radius_i + radius_j - (x_j - x_i), Vec3(vj - vi, 0, 0),
                                       dt};
    return hertz_mindlin_force(material, pair, kinematics, history).force_on_i.x();
  };
  double f = force_on_i(v_i, v_j);
  double overlap = 0.0;
  double time = 0.0;
  for (int step = 0; step < 1000000; ++step) {
    const double half_i = v_i + 0.5 * dt * f / m_i;
    const double half_j = v_j - 0.5 * dt * f / m_j;
    x_i += dt * half_i;
    x_j += dt * half_j;
    f = force_on_i(half_i, half_j); // velocity-dependent part (damping) uses the half-step velocity
    v_i = half_i + 0.5 * dt * f / m_i;
    v_j = half_j - 0.5 * dt * f / m_j;
    const double new_overlap = radius_i + radius_j - (x_j - x_i);
    if (overlap > 0 && new_overlap <= 0) {
      impact.duration = time + dt * overlap / (overlap - new_overlap);
      impact.restitution = (v_j - v_i) / approach_speed;
      return impact;
    }
    overlap = new_overlap;
    time += dt;
  }
  ADD_FAILURE() << "spheres never separated";
  return impact;
}

// 2. Undamped impact: Hertz duration and a restitution coefficient of 1.
TEST(ContactLaw, UndampedImpactMatchesHertzDurationAndIsElastic) {
  const double r_small = 0.5 * kSmallDiameter, r_large = 0.5 * kLargeDiameter;
  struct Case {
    double r_i, r_j, speed;
  };
  for (const Case& c :
       {Case{r_small, r_large, 0.1}, Case{r_large, r_large, 0.01}, Case{r_small, r_small, 1.0}}) {
    SCOPED_TRACE(c.speed);
    const Impact impact = simulate_impact(0.0, c.r_i, c.r_j, c.speed);
    const double duration_error = relative_error(impact.duration, impact.expected_duration);
    std::printf("undamped impact R_i=%g R_j=%g v=%g: duration %.6e s (Hertz %.6e s), rel. error %.2e, "
                "restitution %.9f\n",
                c.r_i, c.r_j, c.speed, impact.duration, impact.expected_duration, duration_error,
                impact.restitution);
    EXPECT_LT(duration_error, 0.01);
    EXPECT_NEAR(impact.restitution, 1.0, 1e-3);
  }
}

TEST(ContactLaw, DampedImpactLosesEnergyMonotonicallyInDampingRatio) {
  const double r_small = 0.5 * kSmallDiameter, r_large = 0.5 * kLargeDiameter;
  double previous = simulate_impact(0.0, r_small, r_large, 0.1).restitution;
  for (const double beta : {0.01, 0.05, 0.1, 0.2, 0.4}) {
    const Impact impact = simulate_impact(beta, r_small, r_large, 0.1);
    std::printf("damping ratio %.2f: restitution %.6f, duration / Hertz %.4f\n", beta, impact.restitution,
                impact.duration / impact.expected_duration);
    EXPECT_LT(impact.restitution, 1.0);
    EXPECT_GT(impact.restitution, 0.0);
    EXPECT_LT(impact.restitution, previous) << "beta " << beta;
    previous = impact.restitution;
  }
}

// c_n = 2 beta sqrt(m* k_n) grows as delta^(1/4): the damped Hertz impact then
// has one restitution coefficient for all impact speeds (dimensional analysis).
TEST(ContactLaw, DampedRestitutionIsIndependentOfImpactSpeed) {
  const double r_small = 0.5 * kSmallDiameter, r_large = 0.5 * kLargeDiameter;
  for (const double beta : {0.05, 0.2}) {
    const double slow = simulate_impact(beta, r_small, r_large, 0.001).restitution;
    const double fast = simulate_impact(beta, r_small, r_large, 1.0).restitution;
    std::printf("damping ratio %.2f: restitution %.6f at 1 mm/s, %.6f at 1 m/s\n", beta, slow, fast);
    EXPECT_NEAR(slow, fast, 1e-6);
  }
}

TEST(ContactLaw, NormalDampingOpposesApproachAndNeverAttracts) {
  const ContactMaterial material = paper_material(0.3);
  const PairProperties pair = paper_pair();
  const double overlap = 1e-8;
  const double f_n = hertz_normal_force(contact_modulus(material), pair.effective_radius, overlap);
  const double k_n = hertz_normal_stiffness(contact_modulus(material), pair.effective_radius, overlap);
  const double c_n = 2.0 * 0.3 * std::sqrt(pair.effective_mass * k_n);
  // Normal along an oblique direction to exercise the vector algebra.
  const Vec3 n = Vec3(1.0, 2.0, -0.5).normalized();
  {
    ContactHistory history;
    const double v_n = -0.01; // j approaches i
    const ContactForce result = hertz_mindlin_force(material, pair, {n, overlap, v_n * n, 1e-9}, history);
    EXPECT_LT(relative_error(result.force_on_i.dot(n), -(f_n - c_n * v_n)), 1e-12);
    EXPECT_LT(result.force_on_i.dot(n), -f_n); // more repulsion than the elastic force alone
    EXPECT_EQ(result.normal_force, f_n);       // normal_force reports the elastic part
  }
  {
    ContactHistory history;
    const double v_n = 10.0 * f_n / c_n; // separating so fast that the damped force would attract
    const ContactForce result = hertz_mindlin_force(material, pair, {n, overlap, v_n * n, 1e-12}, history);
    EXPECT_LE(result.force_on_i.dot(n), 0.0);
    EXPECT_NEAR(result.force_on_i.dot(n), 0.0, 1e-12 * f_n);
  }
}

TEST(ContactLaw, TangentialDampingDragsIAlong) {
  const ContactMaterial material = paper_material(0.2);
  const PairProperties pair = paper_pair();
  const double overlap = 1e-8;
  const double k_t = mindlin_tangential_stiffness(material, pair.effective_radius, overlap);
  const double dt = 1e-9;
  const Vec3 v_t(0.0, 1e-3, 0.0);
  ContactHistory history;
  const ContactForce result = hertz_mindlin_force(material, pair, {Vec3::UnitX(), overlap, v_t, dt}, history);
  const double expected = k_t * v_t.y() * dt + 2.0 * 0.2 * std::sqrt(pair.effective_mass * k_t) * v_t.y();
  EXPECT_LT(relative_error(result.force_on_i.y(), expected), 1e-12);
  EXPECT_GT(result.force_on_i.y(), 0.0);
}

// 3. Tangential loading at constant overlap: slope k_t, Coulomb plateau, elastic unloading.
TEST(ContactLaw, TangentialLoadingSaturatesAtCoulombLimitAndUnloadsElastically) {
  const ContactMaterial material = paper_material();
  const PairProperties pair = paper_pair();
  const double overlap = 2e-8;
  const double f_n = hertz_normal_force(contact_modulus(material), pair.effective_radius, overlap);
  const double k_t = mindlin_tangential_stiffness(material, pair.effective_radius, overlap);
  const double f_max = material.friction * f_n;
  const double slip_displacement = f_max / k_t;

  const double dt = 1e-9;
  const double step = slip_displacement / 1000.0; // tangential displacement per time step
  const Vec3 direction = Vec3(0.0, 3.0, 4.0).normalized();
  const Vec3 normal = Vec3::UnitX();
  ContactHistory history;
  const auto apply = [&](double sign) {
    const ContactKinematics kinematics{normal, overlap, (sign * step / dt) * direction, dt};
    return hertz_mindlin_force(material, pair, kinematics, history);
  };
  const auto tangential = [&](const ContactForce& result) { return result.force_on_i.dot(direction); };

  // Loading: linear with slope k_t until the limit.
  double previous = 0.0;
  int steps = 0;
  for (; steps < 999; ++steps) {
    const ContactForce result = apply(+1.0);
    const double f_t = tangential(result);
    EXPECT_FALSE(history.sliding);
    EXPECT_LT(relative_error((f_t - previous) / step, k_t), 1e-9) << "step " << steps;
    EXPECT_LT(relative_error(result.force_on_i.dot(normal), -f_n), 1e-12);
    EXPECT_NEAR((result.force_on_i - result.force_on_i.dot(normal) * normal - f_t * direction).norm(), 0.0,
                1e-12 * f_max);
    previous = f_t;
  }
  EXPECT_LT(relative_error(previous, 999.0 / 1000.0 * f_max), 1e-9);
  // Past the limit: the force stays at mu F_n and the contact slides.
  for (int k = 0; k < 500; ++k) {
    const ContactForce result = apply(+1.0);
    if (k >= 1) {
      EXPECT_TRUE(history.sliding);
      EXPECT_LT(relative_error(tangential(result), f_max), 1e-12);
      EXPECT_LT(relative_error(history.tangential_force.norm(), f_max), 1e-12); // the history is the force
    }
  }
  // Reversal: elastic unloading with stiffness k_t, through zero to the opposite limit.
  previous = f_max;
  for (int k = 0; k < 1999; ++k) {
    const ContactForce result = apply(-1.0);
    const double f_t = tangential(result);
    EXPECT_FALSE(history.sliding) << "step " << k;
    EXPECT_LT(relative_error((previous - f_t) / step, k_t), 1e-9) << "step " << k;
    previous = f_t;
  }
  for (int k = 0; k < 3; ++k) {
    const ContactForce result = apply(-1.0);
    EXPECT_TRUE(history.sliding);
    EXPECT_LT(relative_error(tangential(result), -f_max), 1e-12);
  }
}

// 3b. Tangential damping acts on a sticking contact only: a sliding contact carries mu F_n
// at any slip rate (a viscous term on top would be a rate-dependent friction).
TEST(ContactLaw, SlidingContactCarriesTheCoulombForceAtAnySlipRate) {
  const double beta = 0.05;
  const ContactMaterial material = paper_material(beta);
  const PairProperties pair = paper_pair();
  const double overlap = 2e-8;
  const double f_n = hertz_normal_force(contact_modulus(material), pair.effective_radius, overlap);
  const double k_t = mindlin_tangential_stiffness(material, pair.effective_radius, overlap);
  const double c_t = 2.0 * beta * std::sqrt(pair.effective_mass * k_t);
  const Vec3 normal = Vec3::UnitX();
  const Vec3 direction = Vec3(0.0, 0.6, 0.8);
  const double dt = 1e-9;
  for (const double speed : {1e-4, 1e-2, 1.0}) {
    ContactHistory history;
    history.tangential_force = material.friction * f_n * direction; // at the limit: any slip slides
    const ContactForce result =
        hertz_mindlin_force(material, pair, {normal, overlap, speed * direction, dt}, history);
    ASSERT_TRUE(history.sliding) << speed;
    const Vec3 tangential = result.force_on_i - result.force_on_i.dot(normal) * normal;
    EXPECT_LT(relative_error(tangential.norm(), material.friction * f_n), 1e-12) << speed;
  }
  // Sticking: the spring increment plus the viscous force c_t v_t.
  ContactHistory history;
  const double speed = 1e-4;
  const ContactForce result =
      hertz_mindlin_force(material, pair, {normal, overlap, speed * direction, dt}, history);
  ASSERT_FALSE(history.sliding);
  const double expected = k_t * speed * dt + c_t * speed;
  EXPECT_LT(relative_error(result.force_on_i.dot(direction), expected), 1e-12);
}

// 4. The elastic tangential force follows the contact plane when the normal turns.
TEST(ContactLaw, SpringTurnsWithTheContactFrame) {
  const ContactMaterial material = paper_material();
  const PairProperties pair = paper_pair();
  const double overlap = 1e-8;
  const double spring_length = 1e-6; // a tangential force [N] well inside the Coulomb limit
  for (const Vec3& axis : {Vec3(0, 0, 1), Vec3(0, 1, 0), Vec3(0.3, -0.2, 0.9).normalized()}) {
    for (const double angle : {1e-6, 1e-3, 0.05}) {
      ContactHistory history;
      history.tangential_force = Vec3(0.0, 1.0, 0.0) * spring_length; // perpendicular to the old normal x
      const Vec3 normal = Eigen::AngleAxisd(angle, axis) * Vec3::UnitX();
      const ContactForce result =
          hertz_mindlin_force(material, pair, {normal, overlap, Vec3::Zero(), 1e-9}, history);
      const Vec3& xi = history.tangential_force;
      EXPECT_LT(relative_error(xi.norm(), spring_length), 1e-14);
      EXPECT_LT(std::abs(xi.dot(normal)), 1e-15 * spring_length);
      EXPECT_FALSE(history.sliding);
      EXPECT_LT((result.force_on_i - (xi - result.normal_force * normal)).norm(),
                1e-14 * result.normal_force);
    }
  }
  // A turn about the old normal (axis x) keeps the spring exactly as it is.
  ContactHistory history;
  history.tangential_force = Vec3(0.0, 2e-12, -1e-12);
  const Vec3 before = history.tangential_force;
  hertz_mindlin_force(material, pair, {Vec3::UnitX(), overlap, Vec3::Zero(), 1e-9}, history);
  EXPECT_EQ(history.tangential_force, before);
  // In-plane rotation about z: the spring is the old one turned by the same angle.
  history.tangential_force = Vec3(0.0, 1e-11, 0.0);
  const double angle = 0.02;
  hertz_mindlin_force(material, pair,
                      {Vec3(std::cos(angle), std::sin(angle), 0.0), overlap, Vec3::Zero(), 1e-9}, history);
  EXPECT_LT((history.tangential_force - 1e-11 * Vec3(-std::sin(angle), std::cos(angle), 0.0)).norm(), 1e-25);
}

TEST(ContactLaw, SeparationResetsHistory) {
  const ContactMaterial material = paper_material(0.1);
  const PairProperties pair = paper_pair();
  for (const double overlap : {0.0, -1e-9}) {
    ContactHistory history;
    history.tangential_force = Vec3(0.0, 1e-9, 0.0);
    history.sliding = true;
    const ContactForce result =
        hertz_mindlin_force(material, pair, {Vec3::UnitX(), overlap, Vec3(-1.0, 1.0, 0.0), 1e-9}, history);
    EXPECT_EQ(result.force_on_i, Vec3::Zero());
    EXPECT_EQ(result.normal_force, 0.0);
    EXPECT_EQ(result.normal_stiffness, 0.0);
    EXPECT_EQ(result.tangential_stiffness, 0.0);
    EXPECT_EQ(history.tangential_force, Vec3::Zero());
    EXPECT_FALSE(history.sliding);
  }
}

// 5. Rayleigh step of the paper's smallest particle.
TEST(ContactLaw, RayleighStepOfSmallestParticle) {
  // D = 0.075 mm: R = 37.5e-6 m; sqrt(rho / G) = sqrt(2650 / 29e9) = 3.022901095716292e-4 s/m;
  // pi R = 1.1780972450961723e-4 m; 0.1631 * 0.15 + 0.8766 = 0.901065;
  // dt_R = 1.1780972450961723e-4 * 3.022901095716292e-4 / 0.901065 = 3.952291403019276e-8 s.
  const double dt = rayleigh_time_step(0.5 * kSmallDiameter, kDensity, paper_material());
  EXPECT_LT(relative_error(dt, 3.952291403019276e-8), 1e-12);
  // Linear in the radius: the largest particle's step is 0.28 / 0.075 times longer.
  EXPECT_LT(relative_error(rayleigh_time_step(0.5 * kLargeDiameter, kDensity, paper_material()),
                           dt * kLargeDiameter / kSmallDiameter),
            1e-12);
}

} // namespace
