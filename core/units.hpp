// Physical constants and unit conversions used at module boundaries (SI inside).
#pragma once

#include <numbers>

namespace sb {

/// Standard gravity [m/s^2]: configs give acceleration levels in g.
inline constexpr double kStandardGravity = 9.80665;
inline constexpr double kPi = std::numbers::pi;
inline constexpr double kTwoPi = 2.0 * std::numbers::pi;

inline constexpr double g_to_m_s2(double level_g) { return level_g * kStandardGravity; }
inline constexpr double m_s2_to_g(double acceleration_m_s2) {
    return acceleration_m_s2 / kStandardGravity;
}
inline constexpr double hz_to_rad_s(double frequency_hz) { return kTwoPi * frequency_hz; }
inline constexpr double deg_to_rad(double angle_deg) { return angle_deg * kPi / 180.0; }

}  // namespace sb
