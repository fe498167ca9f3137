#include "common/shape/ovoid.hpp"

#include "common/error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace aniso {

namespace {

constexpr double pi = std::numbers::pi;
constexpr int n_gauss = 32;

struct GaussRule {
  std::array<double, n_gauss> nodes{};
  std::array<double, n_gauss> weights{};
};

// Gauss-Legendre nodes on [-1, 1] by Newton on P_n from the Chebyshev-like first guess.
GaussRule make_gauss_rule() {
  GaussRule rule;
  for (int i = 0; i < n_gauss; ++i) {
    double x = std::cos(pi * (i + 0.75) / (n_gauss + 0.5));
    double derivative = 1.0;
    for (int iteration = 0; iteration < 100; ++iteration) {
      double p_previous = 1.0;
      double p_current = x;
      for (int k = 2; k <= n_gauss; ++k) {
        const double p_next = ((2.0 * k - 1.0) * x * p_current - (k - 1.0) * p_previous) / k;
        p_previous = p_current;
        p_current = p_next;
      }
      derivative = n_gauss * (x * p_current - p_previous) / (x * x - 1.0);
      const double step = p_current / derivative;
      x -= step;
      if (std::abs(step) < 1e-16) break;
    }
    rule.nodes[static_cast<std::size_t>(i)] = x;
    rule.weights[static_cast<std::size_t>(i)] = 2.0 / ((1.0 - x * x) * derivative * derivative);
  }
  return rule;
}

const GaussRule& gauss_rule() {
  static const GaussRule rule = make_gauss_rule();
  return rule;
}

// One meridian arc: centre (rho, z), radius, and its range of normal angles theta.
struct Arc {
  double centre_rho;
  double centre_z;
  double radius;
  double theta_begin;
  double theta_end;
};

std::array<Arc, 3> meridian_arcs(const OvoidShape& shape) {
  const double beta = shape.splice_angle();
  return {{{0.0, shape.cap_centre_height(), shape.cap_radius(), 0.0, beta},
           {shape.tube_centre_radius(), 0.0, shape.tube_radius(), beta, pi - beta},
           {0.0, -shape.cap_centre_height(), shape.cap_radius(), pi - beta, pi}}};
}

// Integral over theta in [0, pi] of integrand(theta, rho, z, arc_radius), arc by arc.
template <class Integrand> double meridian_integral(const OvoidShape& shape, const Integrand& integrand) {
  const GaussRule& rule = gauss_rule();
  double total = 0.0;
  for (const Arc& arc : meridian_arcs(shape)) {
    const double half = 0.5 * (arc.theta_end - arc.theta_begin);
    const double middle = 0.5 * (arc.theta_end + arc.theta_begin);
    double sum = 0.0;
    for (std::size_t i = 0; i < rule.nodes.size(); ++i) {
      const double theta = middle + half * rule.nodes[i];
      const double rho = arc.centre_rho + arc.radius * std::sin(theta);
      const double z = arc.centre_z + arc.radius * std::cos(theta);
      sum += rule.weights[i] * integrand(theta, rho, z, arc.radius);
    }
    total += half * sum;
  }
  return total;
}

Mat3 axisymmetric(double transverse, double axial) {
  return Vec3(transverse, transverse, axial).asDiagonal();
}

} // namespace

OvoidShape::OvoidShape(double diameter, double aspect_ratio, double splice_angle)
    : diameter_(diameter), aspect_ratio_(aspect_ratio), splice_angle_(splice_angle) {
  require_input(std::isfinite(diameter) && diameter > 0.0,
                fmt::format("ovoid diameter must be positive and finite, got {}", diameter));
  require_input(std::isfinite(aspect_ratio) && aspect_ratio > 0.0 && aspect_ratio <= 1.0,
                fmt::format("ovoid aspect ratio must lie in (0, 1], got {}", aspect_ratio));
  // Tube radius > 0 needs alpha sin(beta) > 1 - cos(beta), i.e. beta < 2 atan(alpha).
  const double beta_limit = aspect_ratio < 1.0 ? 2.0 * std::atan(aspect_ratio) : 0.5 * pi;
  require_input(std::isfinite(splice_angle) && splice_angle > 0.0 && splice_angle < beta_limit,
                fmt::format("ovoid splice angle must lie in (0, {:.6g}) rad = (0, {:.6g}) deg for aspect "
                            "ratio {}, got {:.6g} rad = {:.6g} deg",
                            beta_limit, beta_limit * 180.0 / pi, aspect_ratio, splice_angle,
                            splice_angle * 180.0 / pi));
  const double a = 0.5 * diameter;
  const double c = std::cos(splice_angle);
  const double s = std::sin(splice_angle);
  const double g = s + c - 1.0;
  cos_splice_ = c;
  if (aspect_ratio == 1.0) {
    cap_radius_ = a; // the formulas give a too, up to round-off; keep the sphere exact
    tube_radius_ = a;
  } else {
    cap_radius_ = a * (c - aspect_ratio * (1.0 - s)) / g;
    tube_radius_ = a * (aspect_ratio * s - (1.0 - c)) / g;
  }
  tube_centre_radius_ = a - tube_radius_;
  cap_centre_height_ = aspect_ratio * a - cap_radius_;
}

Vec3 OvoidShape::core_centre(OvoidPiece piece) const {
  switch (piece) {
  case OvoidPiece::top_cap: return {0.0, 0.0, cap_centre_height_};
  case OvoidPiece::bottom_cap: return {0.0, 0.0, -cap_centre_height_};
  case OvoidPiece::band: break;
  }
  return Vec3::Zero();
}

double OvoidShape::piece_radius(OvoidPiece piece) const {
  return piece == OvoidPiece::band ? tube_radius_ : cap_radius_;
}

OvoidPiece OvoidShape::piece_of_normal(const Vec3& normal) const {
  if (normal.z() >= cos_splice_) return OvoidPiece::top_cap;
  if (normal.z() <= -cos_splice_) return OvoidPiece::bottom_cap;
  return OvoidPiece::band;
}

bool OvoidShape::inside(const Vec3& x) const {
  const double rho = std::hypot(x.x(), x.y());
  const double height = std::abs(x.z());
  if (height <= splice_height()) {
    return rho <= tube_centre_radius_ + std::sqrt(tube_radius_ * tube_radius_ - height * height);
  }
  const double dz = height - cap_centre_height_;
  return rho * rho + dz * dz <= cap_radius_ * cap_radius_;
}

OvoidSurfacePoint OvoidShape::closest_point(const Vec3& x) const {
  // The nearest point lies in the half meridian plane through x: find it among the
  // stationary points of the three arcs (feet of the normals through x) and the two splice
  // points, which are always on the surface.
  const double rho = std::hypot(x.x(), x.y());
  const Vec3 radial = rho > 0.0 ? Vec3(x.x() / rho, x.y() / rho, 0.0) : Vec3(1.0, 0.0, 0.0);
  const double beta = splice_angle_;
  const std::array<Arc, 3> arcs = meridian_arcs(*this);
  const std::array<OvoidPiece, 3> pieces{OvoidPiece::top_cap, OvoidPiece::band, OvoidPiece::bottom_cap};

  double best_distance2 = std::numeric_limits<double>::infinity();
  double best_rho = 0.0;
  double best_z = 0.0;
  double best_normal_rho = 0.0;
  double best_normal_z = 1.0;
  OvoidPiece best_piece = OvoidPiece::top_cap;
  const auto consider = [&](double q_rho, double q_z, double n_rho, double n_z, OvoidPiece piece) {
    const double distance2 = (rho - q_rho) * (rho - q_rho) + (x.z() - q_z) * (x.z() - q_z);
    if (distance2 < best_distance2) {
      best_distance2 = distance2;
      best_rho = q_rho;
      best_z = q_z;
      best_normal_rho = n_rho;
      best_normal_z = n_z;
      best_piece = piece;
    }
  };
  for (std::size_t k = 0; k < arcs.size(); ++k) {
    const Arc& arc = arcs[k];
    const double d_rho = rho - arc.centre_rho;
    const double d_z = x.z() - arc.centre_z;
    const double length = std::hypot(d_rho, d_z);
    if (length == 0.0) continue;
    for (const double sign : {1.0, -1.0}) {
      const double n_rho = sign * d_rho / length;
      const double n_z = sign * d_z / length;
      // Caps may use their full circle (either half meridian); the band only its own half.
      const bool in_range = pieces[k] == OvoidPiece::top_cap ? n_z >= cos_splice_
                            : pieces[k] == OvoidPiece::bottom_cap
                                ? n_z <= -cos_splice_
                                : n_rho > 0.0 && std::abs(n_z) <= cos_splice_;
      if (in_range) {
        consider(arc.centre_rho + arc.radius * n_rho, arc.centre_z + arc.radius * n_z, n_rho, n_z, pieces[k]);
      }
    }
  }
  const double splice_rho = splice_radius();
  const double splice_z = splice_height();
  consider(splice_rho, splice_z, std::sin(beta), cos_splice_, OvoidPiece::band);
  consider(splice_rho, -splice_z, std::sin(beta), -cos_splice_, OvoidPiece::band);

  OvoidSurfacePoint result;
  result.point = best_rho * radial + Vec3(0.0, 0.0, best_z);
  result.normal = best_normal_rho * radial + Vec3(0.0, 0.0, best_normal_z);
  const double outward = (rho - best_rho) * best_normal_rho + (x.z() - best_z) * best_normal_z;
  result.signed_distance = outward >= 0.0 ? std::sqrt(best_distance2) : -std::sqrt(best_distance2);
  result.piece = best_piece;
  return result;
}

double OvoidShape::radial_distance(const Vec3& direction) const {
  const double length = direction.norm();
  check_invariant(length > 0.0, "radial_distance needs a nonzero direction");
  const double cos_polar = std::abs(direction.z()) / length;
  const double sin_polar = std::hypot(direction.x(), direction.y()) / length;
  // A ray at or inside the splice point's polar angle meets the cap sphere, else the torus.
  if (sin_polar * splice_height() <= cos_polar * splice_radius()) {
    const double zc = cap_centre_height_;
    return zc * cos_polar + std::sqrt(cap_radius_ * cap_radius_ - zc * zc * sin_polar * sin_polar);
  }
  const double rho0 = tube_centre_radius_;
  return rho0 * sin_polar + std::sqrt(tube_radius_ * tube_radius_ - rho0 * rho0 * cos_polar * cos_polar);
}

OvoidCurvatures OvoidShape::principal_curvatures(const Vec3& x) const {
  const OvoidSurfacePoint surface = closest_point(x);
  const double rho = std::hypot(surface.point.x(), surface.point.y());
  const Vec3 radial =
      rho > 0.0 ? Vec3(surface.point.x() / rho, surface.point.y() / rho, 0.0) : Vec3(1.0, 0.0, 0.0);
  OvoidCurvatures result;
  result.hoop_direction = Vec3(-radial.y(), radial.x(), 0.0);
  result.meridian_direction = result.hoop_direction.cross(surface.normal).normalized();
  if (surface.piece == OvoidPiece::band) {
    result.meridian = 1.0 / tube_radius_;
    // Meusnier: the parallel circle of radius rho has normal curvature sin(theta)/rho, with
    // sin(theta) the radial component of the surface normal.
    result.hoop = surface.normal.dot(radial) / rho;
  } else {
    result.meridian = 1.0 / cap_radius_;
    result.hoop = 1.0 / cap_radius_;
  }
  return result;
}

OvoidSupport OvoidShape::support(const Vec3& direction) const {
  const double length = direction.norm();
  check_invariant(length > 0.0, "support needs a nonzero direction");
  const Vec3 n = direction / length;
  OvoidSupport result;
  result.piece = piece_of_normal(n);
  if (result.piece == OvoidPiece::band) {
    const double transverse = std::hypot(n.x(), n.y()); // > sin(beta) > 0 on the band
    result.point = tube_centre_radius_ / transverse * Vec3(n.x(), n.y(), 0.0) + tube_radius_ * n;
    result.value = tube_centre_radius_ * transverse + tube_radius_;
  } else {
    const double zc = result.piece == OvoidPiece::top_cap ? cap_centre_height_ : -cap_centre_height_;
    result.point = Vec3(0.0, 0.0, zc) + cap_radius_ * n;
    result.value = zc * n.z() + cap_radius_;
  }
  return result;
}

double OvoidShape::volume() const {
  // Two spherical caps above the splice planes plus the band slab |z| <= z_s, whose section
  // has radius rho0 + sqrt(r_t^2 - z^2).
  const double c = cos_splice_;
  const double s = std::sin(splice_angle_);
  const double cap_height = cap_radius_ * (1.0 - c);
  const double cap_volume = pi * cap_height * cap_height * (3.0 * cap_radius_ - cap_height) / 3.0;
  const double rt = tube_radius_;
  const double rho0 = tube_centre_radius_;
  const double zs = rt * c;
  const double root_integral = rt * rt * (c * s + 0.5 * pi - splice_angle_); // of sqrt(r_t^2 - z^2)
  const double band_volume = pi * (2.0 * rho0 * rho0 * zs + 2.0 * rho0 * root_integral + 2.0 * rt * rt * zs -
                                   2.0 * zs * zs * zs / 3.0);
  return 2.0 * cap_volume + band_volume;
}

double OvoidShape::surface_area() const {
  const double c = cos_splice_;
  const double cap_area = 2.0 * pi * cap_radius_ * cap_radius_ * (1.0 - c);
  const double band_area =
      2.0 * pi * tube_radius_ * (tube_centre_radius_ * (pi - 2.0 * splice_angle_) + 2.0 * tube_radius_ * c);
  return 2.0 * cap_area + band_area;
}

Mat3 OvoidShape::inertia_unit_density() const {
  // Slices dz = -R sin(theta) d(theta): a disc of radius rho at height z contributes
  // pi rho^4 / 2 to I_zz and pi rho^4 / 4 + pi rho^2 z^2 to I_xx.
  const double transverse = meridian_integral(*this, [](double theta, double rho, double z, double radius) {
    return pi * rho * rho * (0.25 * rho * rho + z * z) * radius * std::sin(theta);
  });
  const double axial = meridian_integral(*this, [](double theta, double rho, double, double radius) {
    return 0.5 * pi * rho * rho * rho * rho * radius * std::sin(theta);
  });
  return axisymmetric(transverse, axial);
}

OvoidSurfaceTensors OvoidShape::surface_tensors() const {
  // dA = 2 pi rho R d(theta); K dA = 2 pi sin(theta) d(theta) on every piece (Gauss map).
  OvoidSurfaceTensors result;
  result.position = axisymmetric(
      meridian_integral(*this, [](double, double rho, double, double r) { return pi * rho * rho * rho * r; }),
      meridian_integral(*this,
                        [](double, double rho, double z, double r) { return 2.0 * pi * rho * z * z * r; }));
  result.normal = axisymmetric(meridian_integral(*this,
                                                 [](double theta, double rho, double, double r) {
                                                   const double sine = std::sin(theta);
                                                   return pi * sine * sine * rho * r;
                                                 }),
                               meridian_integral(*this, [](double theta, double rho, double, double r) {
                                 const double cosine = std::cos(theta);
                                 return 2.0 * pi * cosine * cosine * rho * r;
                               }));
  result.gaussian_position =
      axisymmetric(meridian_integral(*this, [](double theta, double rho, double,
                                               double) { return pi * rho * rho * std::sin(theta); }),
                   meridian_integral(*this, [](double theta, double, double z, double) {
                     return 2.0 * pi * z * z * std::sin(theta);
                   }));
  return result;
}

namespace {

double spheroid_radius(double half_width, double aspect_ratio, double polar_angle) {
  const double sine = std::sin(polar_angle) / half_width;
  const double cosine = std::cos(polar_angle) / (aspect_ratio * half_width);
  return 1.0 / std::sqrt(sine * sine + cosine * cosine);
}

// Golden-section minimum of a unimodal function on [lower, upper].
template <class Function>
double golden_minimum(const Function& function, double lower, double upper, double tolerance) {
  const double ratio = 0.5 * (std::sqrt(5.0) - 1.0);
  double left = upper - ratio * (upper - lower);
  double right = lower + ratio * (upper - lower);
  double f_left = function(left);
  double f_right = function(right);
  while (upper - lower > tolerance) {
    if (f_left < f_right) {
      upper = right;
      right = left;
      f_right = f_left;
      left = upper - ratio * (upper - lower);
      f_left = function(left);
    } else {
      lower = left;
      left = right;
      f_left = f_right;
      right = lower + ratio * (upper - lower);
      f_right = function(right);
    }
  }
  return 0.5 * (lower + upper);
}

} // namespace

SpheroidComparison compare_with_spheroid(const OvoidShape& shape) {
  const double a = shape.half_width();
  const double alpha = shape.aspect_ratio();
  const auto difference = [&](double polar) {
    return std::abs(shape.radial_distance(Vec3(std::sin(polar), 0.0, std::cos(polar))) -
                    spheroid_radius(a, alpha, polar));
  };
  // Dense scan of the quarter meridian, then a golden refinement around the largest sample.
  constexpr int n_samples = 4000;
  const double step = 0.5 * pi / n_samples;
  double best_polar = 0.0;
  double best_value = -1.0;
  for (int i = 0; i <= n_samples; ++i) {
    const double polar = i * step;
    const double value = difference(polar);
    if (value > best_value) {
      best_value = value;
      best_polar = polar;
    }
  }
  const double lower = std::max(0.0, best_polar - step);
  const double upper = std::min(0.5 * pi, best_polar + step);
  const double refined =
      golden_minimum([&](double polar) { return -difference(polar); }, lower, upper, 1e-12);
  if (difference(refined) > best_value) {
    best_value = difference(refined);
    best_polar = refined;
  }
  const double spheroid_volume = 4.0 / 3.0 * pi * a * a * a * alpha;
  return {(shape.volume() - spheroid_volume) / spheroid_volume, best_value / shape.diameter(), best_polar};
}

double best_splice_angle(double aspect_ratio, SpheroidMatch criterion) {
  require_input(aspect_ratio > 0.0 && aspect_ratio < 1.0,
                fmt::format("best_splice_angle needs an aspect ratio in (0, 1), got {}", aspect_ratio));
  const double upper = 2.0 * std::atan(aspect_ratio);
  const double margin = 1e-9 * upper;
  if (criterion == SpheroidMatch::max_radial_difference) {
    return golden_minimum(
        [&](double beta) {
          return compare_with_spheroid(OvoidShape(1.0, aspect_ratio, beta)).max_radial_difference;
        },
        margin, upper - margin, 1e-10);
  }
  // The volume grows monotonically from below to above the spheroid's as beta falls: bisect.
  const double spheroid_volume = pi / 6.0 * aspect_ratio;
  const auto excess = [&](double beta) {
    return OvoidShape(1.0, aspect_ratio, beta).volume() - spheroid_volume;
  };
  double low = margin;
  double high = upper - margin;
  check_invariant((excess(low) > 0.0) != (excess(high) > 0.0),
                  "ovoid volume does not bracket the spheroid's");
  const bool low_positive = excess(low) > 0.0;
  while (high - low > 1e-13) {
    const double middle = 0.5 * (low + high);
    if ((excess(middle) > 0.0) == low_positive) {
      low = middle;
    } else {
      high = middle;
    }
  }
  return 0.5 * (low + high);
}

} // namespace aniso
