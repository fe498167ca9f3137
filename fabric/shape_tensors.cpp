#include "fabric/shape_tensors.hpp"

#include "common/shape/ovoid.hpp"

#include <numbers>

namespace aniso::fabric {
namespace {

// Unit-diameter sphere (R = 1/2) in closed form: integral x x dA = 4 pi R^4 / 3 I,
// n n dA = 4 pi R^2 / 3 I, K x x dA = (1/R^2)(4 pi R^4 / 3) I.
BodyTensors unit_sphere() {
  constexpr double pi = std::numbers::pi;
  constexpr double r = 0.5;
  BodyTensors t;
  t.position = (4.0 * pi * r * r * r * r / 3.0) * Mat3::Identity();
  t.normal = (4.0 * pi * r * r / 3.0) * Mat3::Identity();
  t.gaussian_position = t.normal;
  t.widths = Mat3::Identity();
  t.area = 4.0 * pi * r * r;
  t.volume = 4.0 * pi * r * r * r / 3.0;
  return t;
}

BodyTensors unit_ovoid(double aspect_ratio, double splice_angle) {
  const OvoidShape shape(1.0, aspect_ratio, splice_angle);
  const OvoidSurfaceTensors s = shape.surface_tensors();
  BodyTensors t;
  t.position = s.position;
  t.normal = s.normal;
  t.gaussian_position = s.gaussian_position;
  t.widths = Vec3(1.0, 1.0, aspect_ratio).asDiagonal();
  t.area = shape.surface_area();
  t.volume = shape.volume();
  return t;
}

} // namespace

BodyTensors ShapeCatalogue::body(double diameter, double aspect_ratio) {
  const Entry* entry = nullptr;
  for (const Entry& e : entries_)
    if (e.aspect_ratio == aspect_ratio) entry = &e;
  if (entry == nullptr) {
    entries_.push_back(
        {aspect_ratio, aspect_ratio == 1.0 ? unit_sphere() : unit_ovoid(aspect_ratio, splice_angle_)});
    entry = &entries_.back();
  }
  const double d2 = diameter * diameter;
  BodyTensors t = entry->unit;
  t.position *= d2 * d2;
  t.normal *= d2;
  t.gaussian_position *= d2;
  t.widths *= diameter;
  t.area *= d2;
  t.volume *= d2 * diameter;
  return t;
}

} // namespace aniso::fabric
