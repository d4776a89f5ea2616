// Magnitudes past which a number in an input file is corruption, not data: every reader
// rejects them with the file, line and field, before they can overflow a map's cell indices,
// an optimizer's sums or an output's fixed-width columns.
#pragma once

namespace lifelong {

/// Positions and relative translations, m: 10 000 km (UTM northings reach 1e7 m).
inline constexpr double kMaxCoordinateM = 1e7;
/// Time stamps, s: 1e10 s is the year 2286 as Unix time.
inline constexpr double kMaxStampS = 1e10;
/// Entries of an information matrix, 1/m^2 or 1/rad^2: a standard deviation of 1e-15 (a
/// published Intel graph reaches 2.7e12).
inline constexpr double kMaxInformation = 1e30;

}  // namespace lifelong
