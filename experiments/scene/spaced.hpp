// The spacing of an axis, shared by the scenes' {lin = [lo, hi], n = N}, {log = [lo, hi], n = N},
// {sqrt = [lo, hi], n = N} and {cbrt = [lo, hi], n = N} (strict_table.hpp: read_axis) and eval's --mu-range and
// --theta-range.
#pragma once

#include <cstdint>
#include <vector>

namespace smithlab::scene {

// The most points one axis may hold: a scene's size is bounded by the work limit (work_estimate.hpp), but an axis
// is made before the work is estimated, so it has its own bound (80 MB of doubles, made in ~0.1 s).
inline constexpr std::int64_t max_axis_points = 10'000'000;

enum class Spacing { lin, log, sqrt, cbrt };

// n >= 2 points from lo to hi, both included, evenly spaced (log: in log, lo > 0; sqrt: in the square root, lo >= 0,
// as roughness alpha is in perceptual roughness; cbrt: in the cube root, lo >= 0, denser at small alpha, where a
// heavy-tailed NDF's albedo changes like ln alpha); the first is lo and the last hi exactly.
std::vector<double> spaced(double lo, double hi, std::int64_t n, Spacing spacing);

}  // namespace smithlab::scene
