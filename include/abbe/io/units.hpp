#pragma once
// Units and constants, named once. abbe computes in mm, µm, µrad and s
// (docs/conventions.md); the factors between them are spelt here so that a
// formula says which conversion it makes.
namespace abbe::units {

inline constexpr double kPi = 3.141592653589793238462643383279502884;
inline constexpr double kTwoPi = 6.283185307179586476925286766559005768;

inline constexpr double kMmPerInch = 25.4;   // exact (1959 definition)
inline constexpr double kUmPerMm = 1e3;      // µm in one mm
inline constexpr double kMmPerUm = 1e-3;     // mm in one µm
inline constexpr double kRadPerUrad = 1e-6;  // rad in one µrad
inline constexpr double kUradPerRad = 1e6;   // µrad in one rad
// An angle in µrad times an arm in mm is a length in nm: this many µm.
inline constexpr double kUmPerUradMm = 1e-3;
inline constexpr double kSecondsPerMinute = 60.0;
inline constexpr double kSecondsPerHour = 3600.0;

}  // namespace abbe::units
