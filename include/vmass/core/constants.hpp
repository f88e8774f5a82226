// Mathematical constants shared by every module (one definition). Header only, constexpr.
#pragma once

namespace vmass {

inline constexpr double kPi = 3.14159265358979323846;

}  // namespace vmass
