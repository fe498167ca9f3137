#include "fabric/measures.hpp"

#include "common/error.hpp"
#include "common/exact_sum.hpp"
#include "common/shape/ovoid.hpp"
#include "common/units.hpp"
#include "fabric/body_intersection.hpp"
#include "fabric/contact_graph.hpp"
#include "fabric/minkowski.hpp"
#include "fabric/shape_tensors.hpp"

#include <cmath>
#include <span>

namespace aniso::fabric {
namespace {

// Exactly summed tensors and scalars, reduced over ranks in one collective.
enum Slot : std::size_t {
  slot_stress_contact,
  slot_stress_kinetic,
  slot_J,
  slot_I,
  slot_S,
  slot_F,
  slot_F_strong,
  slot_G,
  slot_G_strong,
  slot_H,
  slot_H_strong,
  slot_W320,
  n_tensor_slots
};
enum ScalarSlot : std::size_t { scalar_area, scalar_solid_volume, n_scalar_slots };

// Symmetric tensors (everything but the stress and H) sum their upper triangle only.
bool is_symmetric(Slot slot) {
  return slot != slot_stress_contact && slot != slot_H && slot != slot_H_strong;
}

class Sums {
public:
  Sums() : sums_(9 * n_tensor_slots + n_scalar_slots) {}
  void add(Slot slot, const Mat3& m) {
    const bool symmetric = is_symmetric(slot);
    for (int a = 0; a < 3; ++a)
      for (int b = symmetric ? a : 0; b < 3; ++b)
        sums_[index(slot, a, b)].add(m(a, b));
  }
  void add(ScalarSlot slot, double value) { sums_[9 * n_tensor_slots + slot].add(value); }
  void reduce(const mpi::Comm& comm) { sums_ = comm.sum_exact(std::span<const ExactSum>(sums_)); }
  [[nodiscard]] Mat3 tensor(Slot slot) const {
    const bool symmetric = is_symmetric(slot);
    Mat3 m;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        m(a, b) = sums_[symmetric && b < a ? index(slot, b, a) : index(slot, a, b)].value();
    return m;
  }
  [[nodiscard]] double scalar(ScalarSlot slot) const { return sums_[9 * n_tensor_slots + slot].value(); }

private:
  static std::size_t index(Slot slot, int a, int b) { return 9 * slot + static_cast<std::size_t>(3 * a + b); }
  std::vector<ExactSum> sums_;
};

struct Block {
  std::size_t begin, end;
};
Block block_of(std::size_t n, const mpi::Comm& comm) {
  const auto r = static_cast<std::size_t>(comm.rank()), size = static_cast<std::size_t>(comm.size());
  return {n * r / size, n * (r + 1) / size};
}

double splice_angle_of(const h5::Checkpoint& checkpoint) {
  for (const h5::Parameter& p : checkpoint.parameters)
    if (p.name == h5::parameter_name::splice_angle) return p.value;
  return OvoidShape::default_splice_angle;
}

// Messages are built only on failure: this runs over every particle and contact.
void validate(const h5::Checkpoint& c, const std::string& path) {
  const std::size_t n = c.particles.size();
  require_file(n > 0, path + ": the checkpoint holds no particles");
  for (std::size_t k = 0; k < n; ++k) {
    if (c.particles.id[k] != k)
      throw FileError(path + ": /particles/id is not 0..N-1 in order at row " + std::to_string(k));
    const double d = c.particles.diameter[k], alpha = c.particles.aspect_ratio[k];
    if (!(d > 0 && alpha > 0 && alpha <= 1))
      throw FileError(path + ": particle " + std::to_string(k) + " has diameter " + std::to_string(d) +
                      " m and aspect ratio " + std::to_string(alpha) +
                      " (expected D > 0 and 0 < alpha <= 1)");
  }
  for (std::size_t k = 0; k < c.contacts.size(); ++k) {
    const auto [i, j] = c.contacts.particles[k];
    if (!(i < j && j < n))
      throw FileError(path + ": contact " + std::to_string(k) + " joins particles " + std::to_string(i) +
                      " and " + std::to_string(j) + " (expected id_i < id_j < " + std::to_string(n) + ")");
    if (!(std::abs(c.contacts.normal[k].norm() - 1.0) < 1e-9))
      throw FileError(path + ": /contacts/normal row " + std::to_string(k) + " is not a unit vector");
  }
}

Vec3 branch_vector(const h5::Checkpoint& c, std::size_t k) {
  const auto [i, j] = c.contacts.particles[k];
  return c.particles.position[j] + c.contacts.image_shift[k].cast<double>().cwiseProduct(c.cell.lengths) -
         c.particles.position[i];
}

// The share-point test for N_3 and N_4 on this checkpoint's particles.
SharePoint share_point_of(const h5::Checkpoint& c, double splice_angle) {
  return [&c, splice_angle](std::span<const std::uint64_t> ids, std::span<const Vec3> centres) {
    std::array<PlacedBody, 4> bodies{};
    for (std::size_t k = 0; k < ids.size(); ++k)
      bodies[k] = {c.particles.diameter[ids[k]], c.particles.aspect_ratio[ids[k]], splice_angle, centres[k],
                   c.particles.orientation[ids[k]]};
    return bodies_share_point(std::span<const PlacedBody>(bodies.data(), ids.size()));
  };
}

void add_particles(const h5::Checkpoint& c, Block block, double splice_angle, Sums& sums) {
  ShapeCatalogue catalogue(splice_angle);
  const Vec3 centre = 0.5 * c.cell.lengths;
  for (std::size_t k = block.begin; k < block.end; ++k) {
    const BodyTensors body = catalogue.body(c.particles.diameter[k], c.particles.aspect_ratio[k]);
    const Mat3 rotation = c.particles.orientation[k].normalized().toRotationMatrix();
    const auto world = [&rotation](const Mat3& m) -> Mat3 { return rotation * m * rotation.transpose(); };
    sums.add(slot_J, (3.0 / body.widths.trace()) * world(body.widths));     // eq. (Jbar)
    sums.add(slot_I, (3.0 / body.position.trace()) * world(body.position)); // eq. (Ipar)
    sums.add(slot_S, world(body.normal));                                   // eq. (Sbar), before 3/S_v
    sums.add(slot_W320, particle_w320(world(body.gaussian_position) / 3.0,  // eq. (W320)
                                      c.particles.position[k] - centre));
    sums.add(scalar_area, body.area);
    sums.add(scalar_solid_volume, body.volume);
    const Vec3& v = c.particles.velocity[k];
    sums.add(slot_stress_kinetic, -c.particles.mass[k] * v * v.transpose());
  }
}

double normal_force(const h5::Checkpoint& c, std::size_t k) {
  return -c.contacts.force[k].dot(c.contacts.normal[k]); // force on i from j; compression positive
}

std::int64_t add_contacts(const h5::Checkpoint& c, Block block, double strong_above, Sums& sums) {
  const Vec3 centre = 0.5 * c.cell.lengths;
  std::int64_t n_strong = 0;
  for (std::size_t k = block.begin; k < block.end; ++k) {
    const Vec3 l = branch_vector(c, k);
    const Vec3& n = c.contacts.normal[k];
    const Mat3 nn = n * n.transpose(), ll = l * l.transpose(), ln = l * n.transpose();
    sums.add(slot_stress_contact, l * c.contacts.force[k].transpose());
    sums.add(slot_F, nn);
    sums.add(slot_G, ll);
    sums.add(slot_H, ln);
    if (normal_force(c, k) > strong_above) {
      ++n_strong;
      sums.add(slot_F_strong, nn);
      sums.add(slot_G_strong, ll);
      sums.add(slot_H_strong, ln);
    }
    sums.add(slot_W320, contact_w320(c.contacts.point[k] - centre));
  }
  return n_strong;
}

Mat3 mean_or_zero(const Mat3& sum, std::int64_t count, double scale) {
  return count > 0 ? Mat3(sum / (static_cast<double>(count) * scale)) : Mat3::Zero();
}

} // namespace

std::vector<NamedScalar> FabricMeasures::scalars() const {
  const auto count = [](std::int64_t v) { return static_cast<double>(v); };
  return {
      {"time", units::second, "simulated time", time},
      {"step", units::none, "DEM time steps taken", count(step), true},
      {"strain_11", units::none, "engineering strain L1/L1_0 - 1 (compression negative)", strain[0]},
      {"strain_22", units::none, "engineering strain L2/L2_0 - 1", strain[1]},
      {"strain_33", units::none, "engineering strain L3/L3_0 - 1", strain[2]},
      {"n_particles", units::none, "N_p", count(n_particles), true},
      {"n_contacts", units::none, "N_c", count(n_contacts), true},
      {"n_strong", units::none, "contacts with normal force above strong_factor * mean", count(n_strong),
       true},
      {"n_rattlers", units::none, "particles peeled off as rattlers", count(n_rattlers), true},
      {"n_triples", units::none, "N_3: triples of particles sharing a point", count(n_triples), true},
      {"n_quadruples", units::none, "N_4: quadruples of particles sharing a point", count(n_quadruples),
       true},
      {"mean_normal_force", units::newton, "mean contact normal force", mean_normal_force},
      {"p", units::pascal, "mean contact stress, compression positive", mean_stress},
      {"q", units::pascal, "sqrt(3 J2) of the contact stress", deviatoric_stress},
      {"void_ratio", units::none, "e = (V - V_solid) / V_solid", void_ratio},
      {"coordination", units::none, "Z = 2 N_c / N_p", coordination},
      {"coordination_no_rattlers", units::none, "Z without rattlers", coordination_no_rattlers},
      {"chi_paper", units::none, "chi^v = 1 + N_p - N_c, eq. (Chis1)", chi_paper},
      {"chi_paper_per_particle", units::none, "chi^v / N_p, eq. (Chivbar)", chi_paper / count(n_particles)},
      {"chi_torus", units::none, "chi^v = N_p - N_c + N_3 - N_4 of the void on the periodic cell", chi_torus},
      {"chi_torus_per_particle", units::none, "chi_torus / N_p", chi_torus / count(n_particles)},
  };
}

std::vector<NamedTensor> FabricMeasures::tensors() const {
  return {
      {"stress", units::pascal, "contact stress (1/V) sum l (x) f, tension positive", stress_contact},
      {"stress_kinetic", units::pascal,
       "kinetic stress -(1/V) sum m v (x) v; stress + stress_kinetic = DEM stress", stress_kinetic},
      {"J", units::none, "particle axes orientation tensor J^p, eq. (Jbar)", J},
      {"I", units::none, "surface inertia tensor I^s, eq. (Ipar)", I},
      {"S", units::none, "surface normals orientation tensor S^s, eq. (Sbar)", S},
      {"F", units::none, "contact normal orientation tensor F^c, eq. (Fc)", F},
      {"F_strong", units::none, "F^c over strong contacts, eq. (Fcstrong)", F_strong},
      {"G", units::none, "branch vector orientation tensor G^c / D50^2, eq. (Lc)", G},
      {"G_strong", units::none, "G^c over strong contacts, eq. (Lc)", G_strong},
      {"H", units::none, "mixed branch-normal tensor H^c / D50, eq. (Hbarc)", H},
      {"H_strong", units::none, "H^c over strong contacts, eq. (Hbarc)", H_strong},
      {"W320", units::square_metre, "Minkowski tensor W_3^{2,0} about the cell centre, eq. (W320)", W320},
      {"W320_boundary", units::square_metre, "W_3^{2,0} of the cell's boundary box, eqs. (W202), (blocka)",
       W320_boundary},
      {"W320_normalized", units::none, "normalized void Minkowski tensor, eq. (MinkNormal)", W320_normalized},
  };
}

FabricMeasures measure_fabric(const h5::Checkpoint& c, const std::string& path, const FabricConfig& config,
                              const mpi::Comm& comm) {
  validate(c, path);
  const double d50 = h5::parameter(c, h5::parameter_name::d50, path);
  require_file(d50 > 0 && std::isfinite(d50), path + ": parameter d50 must be positive");
  const double splice_angle = splice_angle_of(c);
  const std::size_t n_particles = c.particles.size(), n_contacts = c.contacts.size();

  FabricMeasures m;
  m.source = path;
  m.time = c.time;
  m.step = c.step;
  m.strain = c.cell.lengths.cwiseQuotient(c.cell.reference_lengths) - Vec3::Ones();
  m.n_particles = static_cast<std::int64_t>(n_particles);
  m.n_contacts = static_cast<std::int64_t>(n_contacts);

  const Block particles = block_of(n_particles, comm), contacts = block_of(n_contacts, comm);
  // Pass 1: the mean normal force that separates strong contacts (eq. (Fcstrong)).
  ExactSum force_sum;
  for (std::size_t k = contacts.begin; k < contacts.end; ++k)
    force_sum.add(normal_force(c, k));
  m.mean_normal_force =
      n_contacts ? comm.sum_exact(force_sum).value() / static_cast<double>(n_contacts) : 0.0;

  // Pass 2: every sum.
  Sums sums;
  add_particles(c, particles, splice_angle, sums);
  const std::int64_t strong_here =
      add_contacts(c, contacts, config.strong_factor * m.mean_normal_force, sums);
  const ContactGraph graph(n_particles, c.contacts.particles, c.contacts.image_shift);
  const MultipleOverlaps overlaps_here =
      count_multiple_overlaps(graph, c.contacts.particles, contacts.begin, contacts.end, c.particles.position,
                              c.cell.lengths, share_point_of(c, splice_angle));
  sums.reduce(comm);
  const std::vector<std::int64_t> counts =
      comm.sum(std::vector<std::int64_t>{strong_here, overlaps_here.triples, overlaps_here.quadruples});
  m.n_strong = counts[0];
  m.n_triples = counts[1];
  m.n_quadruples = counts[2];

  const double volume = c.cell.lengths.prod();
  m.stress_contact = sums.tensor(slot_stress_contact) / volume;
  m.stress_kinetic = sums.tensor(slot_stress_kinetic) / volume;
  m.mean_stress = mean_stress_compression_positive(m.stress_contact);
  m.deviatoric_stress = deviatoric_q(m.stress_contact);
  const double solid = sums.scalar(scalar_solid_volume);
  m.void_ratio = (volume - solid) / solid;

  const auto np = static_cast<double>(n_particles);
  m.J = sums.tensor(slot_J) / np;
  m.I = sums.tensor(slot_I) / np;
  m.S = 3.0 * sums.tensor(slot_S) / sums.scalar(scalar_area);
  const auto nc = static_cast<std::int64_t>(n_contacts);
  m.F = mean_or_zero(sums.tensor(slot_F), nc, 1.0);
  m.G = mean_or_zero(sums.tensor(slot_G), nc, d50 * d50);
  m.H = mean_or_zero(sums.tensor(slot_H), nc, d50);
  m.F_strong = mean_or_zero(sums.tensor(slot_F_strong), m.n_strong, 1.0);
  m.G_strong = mean_or_zero(sums.tensor(slot_G_strong), m.n_strong, d50 * d50);
  m.H_strong = mean_or_zero(sums.tensor(slot_H_strong), m.n_strong, d50);
  m.W320 = sums.tensor(slot_W320);
  m.W320_boundary = box_w320(c.cell.lengths);
  m.W320_normalized = normalized_w320(m.W320_boundary, m.W320);

  const Coordination z = coordination(graph, n_contacts, static_cast<int>(config.rattler_min_contacts));
  m.coordination = z.all;
  m.coordination_no_rattlers = z.no_rattlers;
  m.n_rattlers = z.n_rattlers;
  m.chi_paper = 1.0 + np - static_cast<double>(n_contacts); // eq. (Chis1)
  m.chi_torus = np - static_cast<double>(n_contacts) + static_cast<double>(m.n_triples - m.n_quadruples);
  return m;
}

} // namespace aniso::fabric
