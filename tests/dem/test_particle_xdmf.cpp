// Particles and force chains for ParaView (docs/formats/particle-xdmf.md): a hand-built
// checkpoint of four particles (one a rotated ovoid) and two contacts (one across the periodic
// boundary) is written, and the data file read back holds the axis of revolution, the exact
// image point, the force magnitudes and the strong flag; the .xmf names the data file by file
// name with the right counts. Also: no contacts, and a bad output extension.
#include "common/error.hpp"
#include "common/h5/file.hpp"
#include "common/mpi.hpp"
#include "dem/interop/particle_xdmf.hpp"
#include "tests/common/checkpoint_sample.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using aniso::Quat;
using aniso::Vec3;
using aniso::Vec3i;
using aniso::h5::Dims;
using aniso::h5::File;
using ::testing::HasSubstr;
using ::testing::Not;

const double pi = std::numbers::pi;

// Cell and positions are binary fractions, so that the image point is exact.
aniso::h5::Checkpoint four_particles() {
  aniso::h5::Checkpoint c;
  c.time = 0.125;
  c.step = 4321;
  c.cell.lengths = Vec3(0.5, 1.0, 2.0);
  aniso::h5::ParticleRows& p = c.particles;
  p.resize(4);
  const std::vector<Vec3> positions{
      {0.125, 0.25, 0.5}, {0.25, 0.25, 0.5}, {0.0625, 0.5, 1.75}, {0.4375, 0.5, 0.125}};
  for (std::size_t k = 0; k < 4; ++k) {
    p.id[k] = k;
    p.diameter[k] = 0.1 + 0.01 * static_cast<double>(k);
    p.aspect_ratio[k] = 1.0;
    p.mass[k] = 1.0;
    p.inertia[k] = Vec3::Ones();
    p.position[k] = positions[k];
    p.orientation[k] = Quat::Identity();
    p.velocity[k] = Vec3(1, 2, 3) * static_cast<double>(k);
    p.angular_velocity[k] = Vec3(-1, 0, 1) * static_cast<double>(k);
    p.force[k] = Vec3(0, 0, -static_cast<double>(k));
  }
  p.aspect_ratio[1] = 0.625;
  p.orientation[1] = Quat(Eigen::AngleAxisd(pi / 3, Vec3::UnitX())); // body z -> (0, -sin 60, cos 60)
  p.orientation[3] = Quat(Eigen::AngleAxisd(pi / 2, Vec3::UnitY())); // a sphere: its axis stays z

  aniso::h5::ContactRows& k = c.contacts;
  k.resize(2);
  k.particles = {{0, 1}, {2, 3}};
  k.image_shift = {Vec3i(0, 0, 0), Vec3i(-1, 0, 1)}; // 3's image: (0.4375 - 0.5, 0.5, 0.125 + 2)
  k.normal = {Vec3(1, 0, 0), Vec3(-1, 0, 1).normalized()};
  const Vec3 tangent = Vec3(1, 0, 1).normalized();
  k.force = {Vec3(-3, 4, 0), -1.0 * k.normal[1] + 0.5 * tangent + Vec3(0, 0.25, 0)};
  for (std::size_t row = 0; row < 2; ++row) {
    k.point[row] = positions[2 * row];
    k.overlap[row] = 1e-3;
  }
  return c;
}

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

class ParticleXdmf : public ::testing::Test {
protected:
  void SetUp() override {
    folder_ = aniso::test::make_temp_folder(aniso::mpi::Comm(MPI_COMM_SELF), "aniso-particle-xdmf");
    ASSERT_FALSE(folder_.empty());
  }
  void TearDown() override { fs::remove_all(folder_); }
  [[nodiscard]] std::string path(const std::string& name) const {
    return (fs::path(folder_) / name).string();
  }
  std::string folder_;
};

TEST_F(ParticleXdmf, WritesParticlesAndContacts) {
  const auto summary =
      aniso::dem::interop::write_particle_xdmf(four_particles(), "runs/demo/load_001.h5", path("vis.xmf"));
  EXPECT_EQ(summary.xdmf_path, path("vis.xmf"));
  EXPECT_EQ(summary.data_path, path("vis.vis.h5"));
  EXPECT_EQ(summary.particles, 4U);
  EXPECT_EQ(summary.contacts, 2U);
  EXPECT_EQ(summary.strong_contacts, 1U);

  const File file = File::open(summary.data_path);
  EXPECT_EQ(file.read_string_attribute("source"), "runs/demo/load_001.h5");
  EXPECT_EQ(file.read_attribute<std::int64_t>("step"), 4321);
  EXPECT_EQ(file.read_attribute<double>("time"), 0.125);
  EXPECT_EQ(file.read_attribute<double>("cell_length_3"), 2.0);
  EXPECT_EQ(file.read_string_attribute("cell_length_3_units"), "m");

  const auto particles = file.open_group("particles");
  EXPECT_EQ(particles.open_dataset("position").read_string_attribute("units"), "m");
  const std::vector<double> axis = particles.read_dataset<double>("axis", Dims{4, 3});
  EXPECT_NEAR(axis[3], 0.0, 1e-15);
  EXPECT_NEAR(axis[4], -std::sqrt(3.0) / 2, 1e-15);
  EXPECT_NEAR(axis[5], 0.5, 1e-15);
  EXPECT_EQ((std::vector<double>(axis.begin() + 9, axis.end())), (std::vector<double>{0, 0, 1}));
  EXPECT_EQ(particles.read_dataset<std::uint64_t>("id", Dims{4}), (std::vector<std::uint64_t>{0, 1, 2, 3}));
  EXPECT_EQ(particles.read_dataset<double>("diameter", Dims{4}), four_particles().particles.diameter);

  const auto contacts = file.open_group("contacts");
  const std::vector<double> points = contacts.read_dataset<double>("points", Dims{4, 3});
  EXPECT_EQ(points,
            (std::vector<double>{0.125, 0.25, 0.5, 0.25, 0.25, 0.5, 0.0625, 0.5, 1.75, -0.0625, 0.5, 2.125}));
  const std::vector<double> normal = contacts.read_dataset<double>("normal_force", Dims{2});
  const std::vector<double> tangential = contacts.read_dataset<double>("tangential_force", Dims{2});
  EXPECT_NEAR(normal[0], 3.0, 3e-12);
  EXPECT_NEAR(tangential[0], 4.0, 4e-12);
  EXPECT_NEAR(normal[1], 1.0, 1e-12);
  EXPECT_NEAR(tangential[1], std::sqrt(0.5 * 0.5 + 0.25 * 0.25), 1e-12);
  EXPECT_EQ(contacts.read_dataset<std::uint8_t>("strong", Dims{2}), (std::vector<std::uint8_t>{1, 0}));
  EXPECT_EQ(contacts.read_dataset<std::int64_t>("connectivity", Dims{2, 2}),
            (std::vector<std::int64_t>{0, 1, 2, 3}));
  EXPECT_EQ(contacts.open_dataset("normal_force").read_string_attribute("units"), "N");
  EXPECT_EQ(contacts.read_attribute<double>("mean_normal_force"), summary.mean_normal_force);
  EXPECT_NEAR(summary.mean_normal_force, 2.0, 2e-12);

  const std::string xmf = read_text(summary.xdmf_path);
  EXPECT_THAT(xmf, HasSubstr(">vis.vis.h5:/particles/position<"));
  EXPECT_THAT(xmf, HasSubstr(">vis.vis.h5:/contacts/points<"));
  EXPECT_THAT(xmf, Not(HasSubstr(folder_)));
  EXPECT_THAT(xmf, HasSubstr(R"(TopologyType="Polyvertex" NumberOfElements="4")"));
  EXPECT_THAT(xmf, HasSubstr(R"(TopologyType="Polyline" NumberOfElements="2" NodesPerElement="2")"));
  EXPECT_THAT(
      xmf,
      HasSubstr(
          R"(<DataItem Dimensions="4 3" NumberType="Float" Precision="8" Format="HDF">vis.vis.h5:/contacts/points<)"));
  EXPECT_THAT(xmf, HasSubstr(R"(<Grid Name="cell")"));
  // Only the two final files are left (no temporaries).
  EXPECT_EQ(std::distance(fs::directory_iterator(folder_), fs::directory_iterator()), 2);
}

TEST_F(ParticleXdmf, WithoutContactsLeavesOutTheContactGrid) {
  aniso::h5::Checkpoint c = four_particles();
  c.contacts.resize(0);
  const auto summary = aniso::dem::interop::write_particle_xdmf(c, "in.h5", path("none.xmf"));
  EXPECT_EQ(summary.contacts, 0U);
  EXPECT_EQ(summary.strong_contacts, 0U);
  EXPECT_EQ(summary.mean_normal_force, 0.0);
  const File file = File::open(summary.data_path);
  EXPECT_TRUE(file.open_group("contacts").read_dataset<double>("normal_force", Dims{0}).empty());
  EXPECT_EQ(file.open_group("particles").read_dataset<double>("position", Dims{4, 3}).size(), 12U);
  const std::string xmf = read_text(summary.xdmf_path);
  EXPECT_THAT(xmf, HasSubstr(R"(<Grid Name="particles")"));
  EXPECT_THAT(xmf, Not(HasSubstr(R"(<Grid Name="contacts")")));
}

TEST_F(ParticleXdmf, RefusesAnOutputThatIsNotXmf) {
  for (const std::string name : {"vis.h5", "vis.xdmf", ".xmf"}) {
    SCOPED_TRACE(name);
    try {
      aniso::dem::interop::write_particle_xdmf(four_particles(), "in.h5", path(name));
      ADD_FAILURE() << "no InputError";
    } catch (const aniso::InputError& error) {
      EXPECT_THAT(error.what(), HasSubstr(path(name)));
      EXPECT_THAT(error.what(), HasSubstr(".xmf"));
    }
  }
  EXPECT_TRUE(fs::is_empty(folder_));
}

} // namespace
