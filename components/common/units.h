#pragma once

// Units used across StickRep. Lengths are inches (the map's and the paper's unit for edge
// metrics, widths and ranges); speeds are feet per second (the base's rated 2.6 ft/s);
// angles in code are radians unless a name ends in _deg; time is seconds or nanoseconds
// as the name says.
namespace stickrep {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kInchesPerFoot = 12.0;

constexpr double DegToRad(double deg) { return deg * kPi / 180.0; }
constexpr double RadToDeg(double rad) { return rad * 180.0 / kPi; }
constexpr double FeetToInches(double ft) { return ft * kInchesPerFoot; }
constexpr double InchesToFeet(double in) { return in / kInchesPerFoot; }

}  // namespace stickrep
