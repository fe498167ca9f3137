// The allowed ranges of the DEM settings that a checkpoint stores in /parameters, shared by the
// config reader (dem/config.cpp) and the checkpoint reader (dem/io/checkpoint.cpp), so that a file cannot
// carry what the configuration would refuse (a Poisson ratio of 0.7, a control interval of 0).
#pragma once

#include "common/config.hpp"

namespace aniso::dem::io::ranges {

using config::Range;

inline Range shear_modulus() {
  return Range::positive();
}
inline Range poisson_ratio() {
  return Range::open(-1.0, 0.5);
}
inline Range friction() {
  return Range::non_negative();
}
inline Range contact_damping() {
  return Range::closed(0.0, 1.0);
}
inline Range density() {
  return Range::positive();
}
inline Range length() {
  return Range::positive();
} ///< skin in metres
/// Particle diameters in metres, from a nanometre to a kilometre: far smaller sizes underflow the
/// volumes and inertias (d^5) that the simulation needs, and the range covers every granular
/// material from clay to boulders.
inline Range diameter() {
  return Range::closed(1e-9, 1e3);
}
inline Range global_damping() {
  return Range::closed(0.0, 10.0);
}
inline Range control_interval() {
  return Range::closed(1, 1e6);
}
inline Range servo_gain() {
  return Range::open_closed(0.0, 1.0);
}
inline Range explosion_overlap() {
  return Range::open(0.0, 1.0);
}
inline Range aspect_ratio() {
  return Range::open_closed(0.2, 1.0);
}
inline Range splice_angle_degrees() {
  return Range::open(0.0, 90.0);
}

} // namespace aniso::dem::io::ranges
