#pragma once
// The paper's particle sizes and the default skin, for tests that place particles by hand.

namespace aniso::dem::test {

constexpr double kRadiusMin = 0.0375e-3; ///< half the smallest diameter, 0.075 mm [m]
constexpr double kRadiusMax = 0.14e-3;   ///< half the largest diameter, 0.28 mm [m]
constexpr double kDensity = 2650.0;      ///< [kg/m^3]
constexpr double kSkin = 0.017e-3;       ///< 0.1 D50 [m]

} // namespace aniso::dem::test
