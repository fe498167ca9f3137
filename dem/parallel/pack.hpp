#pragma once
// Vectors and quaternions into and out of the byte buffers that travel between ranks
// (common/exchange.hpp), component by component: Eigen's types are not trivially copyable.

#include "common/exchange.hpp"
#include "common/tensor.hpp"

namespace aniso::dem::parallel {

inline void put_vec3(ByteWriter& out, const Vec3& v) {
  out.put(v[0]);
  out.put(v[1]);
  out.put(v[2]);
}

inline Vec3 get_vec3(ByteReader& in) {
  const double x = in.get<double>(), y = in.get<double>(), z = in.get<double>();
  return {x, y, z};
}

inline void put_quat(ByteWriter& out, const Quat& q) {
  out.put(q.w());
  out.put(q.x());
  out.put(q.y());
  out.put(q.z());
}

inline Quat get_quat(ByteReader& in) {
  const double w = in.get<double>(), x = in.get<double>(), y = in.get<double>(), z = in.get<double>();
  return {w, x, y, z};
}

} // namespace aniso::dem::parallel
