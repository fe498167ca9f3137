#pragma once
// SI unit labels written as HDF5 `units` attributes and shown by --print-config.

namespace aniso::units {

inline constexpr const char* none = "1";
inline constexpr const char* metre = "m";
inline constexpr const char* square_metre = "m^2";
inline constexpr const char* cubic_metre = "m^3";
inline constexpr const char* second = "s";
inline constexpr const char* per_second = "1/s";
inline constexpr const char* kilogram = "kg";
inline constexpr const char* kilogram_square_metre = "kg m^2";
inline constexpr const char* density = "kg/m^3";
inline constexpr const char* pascal = "Pa";
inline constexpr const char* newton = "N";
inline constexpr const char* joule = "J";
inline constexpr const char* velocity = "m/s";
inline constexpr const char* angular_velocity = "rad/s";
inline constexpr const char* radian = "rad";

} // namespace aniso::units
