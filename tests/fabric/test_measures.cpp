// measure_fabric on hand-built checkpoints with known answers: identity tensors for spheres,
// rotated body-frame tensors for one ovoid, exact F, G, H, coordination and both chi on lattices.
#include "common/shape/ovoid.hpp"
#include "fabric/measures.hpp"
#include "fabric/minkowski.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>

#include "synthetic.hpp"

namespace aniso::fabric {
namespace {

using test::Lattice;
using test::LatticeSpec;

const mpi::Comm self(MPI_COMM_SELF);

void expect_matrix_near(const Mat3& actual, const Mat3& expected, double tolerance, const char* what) {
  EXPECT_LE((actual - expected).cwiseAbs().maxCoeff(), tolerance) << what << ":\n"
                                                                  << actual << "\nexpected\n"
                                                                  << expected;
}

// measure_fabric hashes its source file; the tests write each checkpoint first.
FabricMeasures measure_written(const h5::Checkpoint& c, const std::string& name) {
  const std::string path = ::testing::TempDir() + name;
  h5::write_checkpoint(path, c, test::test_provenance(), self);
  return measure_fabric(c, path, FabricConfig{}, self);
}

TEST(FabricSpheres, ParticleAndSurfaceTensorsAreIdentityForAnyOrientation) {
  LatticeSpec spec;
  spec.kind = Lattice::fcc;
  spec.cells = 2;
  spec.spacing = 0.99e-3;
  spec.jitter = 0.005;
  spec.random_orientations = true;
  const FabricMeasures m = measure_written(test::lattice_checkpoint(spec), "spheres.h5");
  expect_matrix_near(m.J, Mat3::Identity(), 1e-15, "J");
  expect_matrix_near(m.I, Mat3::Identity(), 1e-14, "I");
  expect_matrix_near(m.S, Mat3::Identity(), 1e-14, "S");
}

TEST(FabricOvoid, SingleRotatedOvoidGivesTheRotatedBodyTensors) {
  const double D = 1e-3, alpha = 0.5;
  const OvoidShape shape(D, alpha);
  const OvoidSurfaceTensors body = shape.surface_tensors();
  const Mat3 I_body = (3.0 / body.position.trace()) * body.position;
  const Mat3 S_body = (3.0 / body.normal.trace()) * body.normal;
  const Mat3 J_body = (3.0 / (2.0 + alpha)) * Vec3(1.0, 1.0, alpha).asDiagonal().toDenseMatrix();
  const Vec3 L = Vec3::Constant(4 * D);
  // A quarter turn about x1 takes the axis of revolution (body z) to world x2: diagonals permute.
  const Quat quarter(Eigen::AngleAxisd(std::numbers::pi / 2, Vec3::UnitX()));
  const Quat general = Quat(0.3, -0.5, 0.7, 0.2).normalized();
  for (const Quat& q : {Quat::Identity(), quarter, general}) {
    h5::Checkpoint c = test::empty_checkpoint(L, L, D);
    test::add_particle(c, D, alpha, 0.5 * L, q);
    const FabricMeasures m = measure_written(c, "ovoid.h5");
    const Mat3 R = q.toRotationMatrix();
    expect_matrix_near(m.J, R * J_body * R.transpose(), 1e-15, "J");
    expect_matrix_near(m.I, R * I_body * R.transpose(), 1e-14, "I");
    expect_matrix_near(m.S, R * S_body * R.transpose(), 1e-14, "S");
    EXPECT_NEAR(m.void_ratio, (L.prod() - shape.volume()) / shape.volume(), 1e-12);
  }
  // The quarter turn in closed form: J = 3/(2 + alpha) diag(1, alpha, 1).
  h5::Checkpoint c = test::empty_checkpoint(L, L, D);
  test::add_particle(c, D, alpha, 0.5 * L, quarter);
  const FabricMeasures m = measure_written(c, "ovoid_quarter.h5");
  expect_matrix_near(m.J, (3.0 / 2.5) * Vec3(1.0, alpha, 1.0).asDiagonal().toDenseMatrix(), 1e-15,
                     "J quarter");
  EXPECT_NEAR(m.I(1, 1), I_body(2, 2), 1e-14);
  EXPECT_NEAR(m.I(2, 2), I_body(1, 1), 1e-14);
  // Oblate: the surface normals gather along the axis, the surface inertia across it.
  EXPECT_GT(S_body(2, 2), S_body(0, 0));
  EXPECT_LT(I_body(2, 2), I_body(0, 0));
}

TEST(FabricOvoid, TripleOverlapOfFlatOvoidsEntersChiOnTheTorus) {
  // Three flat ovoids (alpha 0.5, D = 1 mm) 0.8 mm apart in a plane: lying flat they share the
  // triangle's centre (N_3 = 1, chi_torus = 3 - 3 + 1); standing on edge, facing away from the
  // centre, they do not (N_3 = 0) although the contact list is the same.
  const double D = 1e-3, d = 0.8e-3;
  const Vec3 L = Vec3::Constant(5e-3), o(2e-3, 2e-3, 2.5e-3);
  const std::array<Vec3, 3> centres{o, o + Vec3(d, 0, 0), o + Vec3(0.5 * d, 0.5 * std::sqrt(3.0) * d, 0)};
  const Vec3 middle = (centres[0] + centres[1] + centres[2]) / 3.0;
  for (const bool flat : {true, false}) {
    h5::Checkpoint c = test::empty_checkpoint(L, L, D);
    for (const Vec3& x : centres)
      test::add_particle(c, D, 0.5, x,
                         flat ? Quat::Identity() : Quat::FromTwoVectors(Vec3::UnitZ(), x - middle));
    for (std::uint64_t i = 0; i < 3; ++i)
      for (std::uint64_t j = i + 1; j < 3; ++j) {
        const Vec3 n = (centres[j] - centres[i]).normalized();
        c.contacts.particles.push_back({i, j});
        c.contacts.image_shift.push_back(Vec3i::Zero());
        c.contacts.normal.push_back(n);
        c.contacts.point.push_back(0.5 * (centres[i] + centres[j]));
        c.contacts.overlap.push_back(0.2e-3);
        c.contacts.force.push_back(-1e-3 * n);
        c.contacts.tangential_force.push_back(Vec3::Zero());
        c.contacts.sliding.push_back(0);
      }
    const FabricMeasures m = measure_written(c, "ovoid_triple.h5");
    EXPECT_EQ(m.n_triples, flat ? 1 : 0) << (flat ? "flat" : "standing");
    EXPECT_EQ(m.chi_paper, 1.0 + 3 - 3);
    EXPECT_EQ(m.chi_torus, flat ? 1.0 : 0.0);
  }
}

TEST(FabricLattice, SimpleCubicGivesExactContactTensorsAndChi) {
  LatticeSpec spec; // 4^3 = 64 spheres of D = 1 mm at spacing 0.98 mm: 6 contacts each
  const FabricMeasures m = measure_written(test::lattice_checkpoint(spec), "sc.h5");
  const double s = spec.spacing / spec.diameter;
  ASSERT_EQ(m.n_particles, 64);
  EXPECT_EQ(m.n_contacts, 192);
  EXPECT_EQ(m.coordination, 6.0);
  EXPECT_EQ(m.coordination_no_rattlers, 6.0);
  EXPECT_EQ(m.n_rattlers, 0);
  EXPECT_EQ(m.n_triples, 0); // no triangles in the simple cubic contact graph
  EXPECT_EQ(m.n_quadruples, 0);
  EXPECT_EQ(m.chi_paper, 1.0 + 64 - 192);
  EXPECT_EQ(m.chi_torus, 64.0 - 192);
  expect_matrix_near(m.F, Mat3::Identity() / 3.0, 1e-15, "F");
  expect_matrix_near(m.G, s * s * Mat3::Identity() / 3.0, 1e-14, "G");
  expect_matrix_near(m.H, s * Mat3::Identity() / 3.0, 1e-14, "H");
  // Equal forces everywhere: no contact is above the mean, so the strong tensors are empty.
  EXPECT_EQ(m.n_strong, 0);
  EXPECT_EQ(m.F_strong, Mat3::Zero());
}

TEST(FabricLattice, FccCountsTripleAndQuadrupleOverlapsExactly) {
  // FCC with nearest-neighbour distance d: 12 contacts per sphere, 8 triangles per sphere
  // (faces of the 2 tetrahedra and 1 octahedron per sphere, each face shared by one of each).
  // Three spheres of a face share a point iff d <= sqrt(3) R; the four of a tetrahedron iff
  // d <= sqrt(8/3) R. Octahedra (6 spheres about a point at d / sqrt(2)) never meet here.
  for (const double d_over_D : {0.90, 0.85, 0.80}) {
    LatticeSpec spec;
    spec.kind = Lattice::fcc;
    spec.cells = 2;
    spec.spacing = d_over_D * spec.diameter;
    const FabricMeasures m = measure_written(test::lattice_checkpoint(spec), "fcc.h5");
    const std::int64_t N = 32;
    ASSERT_EQ(m.n_particles, N);
    EXPECT_EQ(m.n_contacts, 6 * N);
    const std::int64_t triples = d_over_D <= std::sqrt(3.0) / 2 ? 8 * N : 0;
    const std::int64_t quadruples = d_over_D <= std::sqrt(8.0 / 3.0) / 2 ? 2 * N : 0;
    EXPECT_EQ(m.n_triples, triples) << "d/D = " << d_over_D;
    EXPECT_EQ(m.n_quadruples, quadruples) << "d/D = " << d_over_D;
    EXPECT_EQ(m.chi_paper, 1.0 + static_cast<double>(N - 6 * N));
    EXPECT_EQ(m.chi_torus, static_cast<double>(N - 6 * N + triples - quadruples));
    expect_matrix_near(m.F, Mat3::Identity() / 3.0, 1e-15, "F");
    expect_matrix_near(m.G, d_over_D * d_over_D * Mat3::Identity() / 3.0, 1e-14, "G");
    expect_matrix_near(m.H, d_over_D * Mat3::Identity() / 3.0, 1e-14, "H");
  }
}

TEST(FabricLattice, StretchedJitteredLatticeSplitsStrongContactsAndIsAnisotropic) {
  // Compressing x1 by 2% and extending x3: contacts along x1 carry more force; the strong subset
  // is exactly the contacts above the mean normal force and F leans towards x1.
  LatticeSpec spec;
  spec.kind = Lattice::fcc;
  spec.cells = 3;
  spec.spacing = 0.995e-3;
  spec.stretch = Vec3(0.98, 1.0, 1.02);
  spec.jitter = 0.002;
  const h5::Checkpoint c = test::lattice_checkpoint(spec);
  const FabricMeasures m = measure_written(c, "stretched.h5");
  double sum = 0;
  for (const Vec3& f : c.contacts.force)
    sum += f.norm() / std::sqrt(1.01);
  std::int64_t strong = 0;
  const double mean = m.mean_normal_force;
  for (std::size_t k = 0; k < c.contacts.size(); ++k)
    strong += (-c.contacts.force[k].dot(c.contacts.normal[k]) > mean) ? 1 : 0;
  EXPECT_NEAR(mean, sum / static_cast<double>(c.contacts.size()), 1e-9 * mean);
  EXPECT_EQ(m.n_strong, strong);
  EXPECT_GT(m.n_strong, 0);
  EXPECT_GT(m.F(0, 0), m.F(2, 2));
  EXPECT_GT(m.F_strong(0, 0) - m.F_strong(2, 2), m.F(0, 0) - m.F(2, 2));
  EXPECT_NEAR(m.F.trace(), 1.0, 1e-15);
  EXPECT_NEAR(m.strain[0], -0.02, 1e-15);
  // Stress from its definition, summed here independently.
  Mat3 stress = Mat3::Zero();
  for (std::size_t k = 0; k < c.contacts.size(); ++k) {
    const auto [i, j] = c.contacts.particles[k];
    const Vec3 l = c.particles.position[j] +
                   c.contacts.image_shift[k].cast<double>().cwiseProduct(c.cell.lengths) -
                   c.particles.position[i];
    stress += l * c.contacts.force[k].transpose();
  }
  stress /= c.cell.lengths.prod();
  expect_matrix_near(m.stress_contact, stress, 1e-12 * stress.norm(), "stress");
  EXPECT_GT(-m.stress_contact(0, 0), -m.stress_contact(2, 2));
}

TEST(FabricMinkowski, IsolatedSphereAndContactFollowEquationW320) {
  // Two spheres touching across the cell: W320 = sum of particle terms minus (4 pi / 3) x_c x_c,
  // about the cell centre, and the normalisation by the boundary box (eq. (MinkNormal)).
  const double D = 1e-3;
  const Vec3 L(4e-3, 3e-3, 5e-3);
  h5::Checkpoint c = test::empty_checkpoint(L, L, D);
  test::add_particle(c, D, 1.0, Vec3(0.3e-3, 1.0e-3, 2.0e-3), Quat::Identity());
  test::add_particle(c, D, 1.0, Vec3(3.31e-3, 1.0e-3, 2.0e-3), Quat::Identity()); // touches 0 through x1 = 0
  test::add_contacts(c, 0.0);
  ASSERT_EQ(c.contacts.size(), 1U);
  const FabricMeasures m = measure_written(c, "w320.h5");
  const double R = 0.5 * D, w3 = 4.0 * std::numbers::pi / 3.0;
  Mat3 expected = Mat3::Zero();
  for (const Vec3& x : c.particles.position) {
    const Vec3 t = x - 0.5 * L;
    expected += (4.0 * std::numbers::pi / 9.0) * R * R * Mat3::Identity() + w3 * t * t.transpose();
  }
  const Vec3 xc = c.contacts.point[0] - 0.5 * L;
  expected -= w3 * xc * xc.transpose();
  expect_matrix_near(m.W320, expected, 1e-14 * expected.norm(), "W320");
  expect_matrix_near(m.W320_boundary, box_w320(L), 0, "boundary");
  expect_matrix_near(m.W320_normalized, box_w320(L).inverse() * expected, 1e-13, "normalized");
  EXPECT_EQ(m.chi_paper, 2.0);
  EXPECT_EQ(m.chi_torus, 1.0);
}

} // namespace
} // namespace aniso::fabric
