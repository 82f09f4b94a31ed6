// smithlab/rng.hpp -- the random numbers every sampler draws: a PCG generator (O'Neill 2014, pcg-cpp) that callers
// own and pass in. No global state: the same seed gives the same samples.
#pragma once

#include <cstdint>
#include <pcg_random.hpp>

namespace smithlab {

using Rng = pcg64;

// A generator for `seed` and stream `stream` (independent sequences for, e.g., one per thread or per estimate).
inline Rng make_rng(std::uint64_t seed, std::uint64_t stream = 0) { return Rng(seed, stream); }

// Uniform in [0, 1): the top 53 bits, so every value is a multiple of 2^-53 and 1 is never returned.
inline double uniform01(Rng& g) { return static_cast<double>(g() >> 11) * 0x1.0p-53; }

}  // namespace smithlab
