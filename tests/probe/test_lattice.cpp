// Analytic validation: a simple cubic lattice of equal Hertz spheres in a periodic cell,
// compressed so that every sphere touches its six neighbours with overlap delta0. An axial
// increment d eps_11 changes only the x1 contacts' overlaps (by -s d eps_11) and, through the
// cross-section, the stress carried by the other chains, so
//   C_ii = k_n / s,  C_ij = p (i != j),
// with s the spacing, k_n = dF/d delta the Hertz normal stiffness at delta0 and p = F / s^2, and D
// the curvature of the Hertz law over the increment (below).
// The forks must reproduce this; the reference fork stays at rest (the lattice is static).
#include "common/h5/checkpoint.hpp"
#include "common/log.hpp"
#include "dem/io/parameters.hpp"
#include "dem/model/contact_law.hpp"
#include "probe/collect.hpp"
#include "probe/schedule.hpp"
#include "probe/source.hpp"
#include "tests/dem/assembly_fixture.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

namespace aniso::probe {
namespace {

constexpr int cells = 5;
constexpr double diameter = 0.2e-3;
constexpr double spacing = 0.999 * diameter; // overlap 2e-7 m: p of order 100 kPa

dem::model::ContactMaterial material() {
  dem::model::ContactMaterial m;
  m.shear_modulus = 29e9;
  m.poisson_ratio = 0.15;
  m.friction = 0.5;
  m.damping_ratio = 0.05;
  return m;
}

double hertz(double overlap) {
  return dem::model::hertz_normal_force(dem::model::contact_modulus(material()), 0.25 * diameter, overlap);
}

// The lattice at rest with its contacts and the parameters the DEM restores from.
h5::Checkpoint lattice() {
  const dem::model::ContactMaterial m = material();
  h5::Checkpoint c;
  c.time_step = 0.2 * dem::model::rayleigh_time_step(0.5 * diameter, 2650.0, m);
  c.cell.lengths = Vec3::Constant(cells * spacing);
  c.cell.reference_lengths = c.cell.lengths;
  c.cell.mode = {h5::AxisMode::strain_rate, h5::AxisMode::strain_rate, h5::AxisMode::strain_rate};
  dem::SimulationSettings settings;
  settings.material = m;
  settings.density = 2650.0;
  settings.d50 = diameter;
  settings.skin = 0.1 * diameter;
  settings.control_interval = 10;
  c.parameters = dem::io::stored_parameters(settings); // every parameter a checkpoint stores
  c.parameters.push_back({"global_damping_rate", 0.0, "1/s"});
  const double mass = 2650.0 * std::numbers::pi * diameter * diameter * diameter / 6.0;
  const auto index = [](int x, int y, int z) {
    return static_cast<std::uint64_t>((x * cells + y) * cells + z);
  };
  c.particles.resize(cells * cells * cells);
  for (int x = 0; x < cells; ++x) {
    for (int y = 0; y < cells; ++y) {
      for (int z = 0; z < cells; ++z) {
        const std::size_t k = index(x, y, z);
        c.particles.id[k] = k;
        c.particles.diameter[k] = diameter;
        c.particles.aspect_ratio[k] = 1.0;
        c.particles.mass[k] = mass;
        c.particles.inertia[k] = Vec3::Constant(0.1 * mass * diameter * diameter);
        c.particles.position[k] = (Vec3(x, y, z) + Vec3::Constant(0.5)) * spacing;
        c.particles.orientation[k] = Quat::Identity();
        c.particles.velocity[k] = c.particles.angular_velocity[k] = Vec3::Zero();
        c.particles.force[k] = c.particles.torque[k] = Vec3::Zero(); // balanced by symmetry
      }
    }
  }
  const double overlap = diameter - spacing;
  for (int x = 0; x < cells; ++x) {
    for (int y = 0; y < cells; ++y) {
      for (int z = 0; z < cells; ++z) {
        const int here[3] = {x, y, z};
        for (int a = 0; a < 3; ++a) {
          int there[3] = {x, y, z};
          there[a] = (here[a] + 1) % cells;
          Vec3i shift = Vec3i::Zero();
          if (there[a] == 0) shift[a] = 1; // the neighbour across the periodic boundary
          std::uint64_t i = index(x, y, z), j = index(there[0], there[1], there[2]);
          Vec3 normal = Vec3::Unit(a);
          if (i > j) { // rows are stored with id_i < id_j
            std::swap(i, j);
            normal = -normal;
            shift = -shift;
          }
          c.contacts.particles.push_back({i, j});
          c.contacts.image_shift.push_back(shift);
          c.contacts.normal.push_back(normal);
          Vec3 point = c.particles.position[i] + 0.5 * spacing * normal;
          for (int b = 0; b < 3; ++b)
            point[b] -= std::floor(point[b] / c.cell.lengths[b]) * c.cell.lengths[b];
          c.contacts.point.push_back(point);
          c.contacts.overlap.push_back(overlap);
          c.contacts.force.push_back(-hertz(overlap) * normal);
          c.contacts.tangential_force.push_back(Vec3::Zero());
          c.contacts.sliding.push_back(0);
        }
      }
    }
  }
  return c;
}

TEST(ProbeLattice, SimpleCubicHertzLatticeMatchesTheAnalyticStiffness) {
  const dem::test::TemporaryFolder folder("probe_lattice");
  const std::string path = folder.file("lattice.h5");
  const mpi::Comm comm = mpi::Comm::world();
  h5::write_checkpoint(path, lattice(), dem::test::test_provenance(), comm);
  const h5::Checkpoint checkpoint = h5::read_checkpoint(path, comm);
  const ProbeConfig config;
  const auto results = run_all_forks(checkpoint, path, config, comm, make_silent_logger());
  std::array<ForkFile, n_fork_files> forks;
  for (int k = 0; k < n_fork_files; ++k)
    forks[static_cast<std::size_t>(k)] = {probe_source(path, checkpoint, comm), fork_settings(config),
                                          results[static_cast<std::size_t>(k)]};
  std::string warning;
  const ProbeResult result = assemble_result(forks, config, warning);
  EXPECT_EQ(warning, "");

  const double overlap = diameter - spacing, h = 1e-3 * overlap;
  const double k_n = (hertz(overlap + h) - hertz(overlap - h)) / (2 * h);
  const double p = hertz(overlap) / (spacing * spacing);
  const Mat3& C = result.stiffness.C;
  std::printf(
      "lattice: C11 C22 C33 = %.6g %.6g %.6g Pa against k_n/s = %.6g Pa; C12 C21 = %.6g %.6g against p = "
      "%.6g Pa; max |D| = %.4g Pa\n",
      C(0, 0), C(1, 1), C(2, 2), k_n / spacing, C(0, 1), C(1, 0), p,
      result.stiffness.D.cwiseAbs().maxCoeff());
  // The reference fork stays at the lattice's stress: it is static.
  EXPECT_NEAR(mean_stress_compression_positive(result.stress_reference), p, 1e-6 * p);
  // C averages the extension and compression secants, which cancels the Hertz curvature to second
  // order; D is that curvature: Q+-_ii = k_n/s -+ F'' delta / 2 with F'' = k_n / (2 delta0), so
  // D_ii = -(k_n/s) s delta / (4 delta0) (-1.25% of C_ii here). The lateral terms carry no curvature.
  const double d_ii = -(k_n / spacing) * spacing * config.increment / (4 * overlap);
  const Mat3& D = result.stiffness.D;
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(C(i, i), k_n / spacing, 1e-3 * k_n / spacing) << "C = \n" << C;
    EXPECT_NEAR(D(i, i), d_ii, 0.05 * std::abs(d_ii)) << "D = \n" << D;
    for (int j = 0; j < 3; ++j) {
      if (i != j) {
        EXPECT_NEAR(C(i, j), p, 1e-3 * p) << i << j << " C = \n" << C;
        EXPECT_LT(std::abs(D(i, j)), 1e-3 * p) << i << j << " D = \n" << D;
      }
    }
  }
}

} // namespace
} // namespace aniso::probe
