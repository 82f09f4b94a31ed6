/// @file
/// smithlab/rng.hpp -- the random numbers every sampler draws. No global state: generators are values the caller
/// owns and passes in, and the same seed gives the same samples.
///
///   Rng      a PCG generator (O'Neill 2014, pcg-cpp), for sequential streams (`smithlab sample`, the tests).
///   WalkRng  a counter-based generator (Salmon, Moraes, Dror, Shaw 2011, "Parallel random numbers: as easy as
///            1, 2, 3", Philox4x64-10 from Random123) keyed by (seed, cell) and counting from (walk, 0): the numbers of
///            walk k of a cell are a pure function of (seed, cell, k), whichever thread or process runs it.
#pragma once

#include <Random123/philox.h>

#include <concepts>
#include <cstdint>
#include <limits>
#include <pcg_random.hpp>
#include <random>

namespace smithlab {

/// The sequential generator: pcg64 (O'Neill 2014).
using Rng = pcg64;

/// A generator for `seed` and stream `stream` (independent sequences for, e.g., one per thread or per estimate).
inline Rng make_rng(std::uint64_t seed, std::uint64_t stream = 0) { return Rng(seed, stream); }

/// The counter-based generator of the walks: Philox4x64-10 (Salmon et al. 2011) keyed by (seed, cell), counting from
/// (walk, 0); a uniform random bit generator of 64-bit numbers.
class WalkRng {
public:
    /// The numbers drawn: 64 bits, from min() = 0 to max() = 2^64 - 1.
    /// @{
    using result_type = std::uint64_t;
    static constexpr result_type min() { return 0; }
    static constexpr result_type max() { return std::numeric_limits<result_type>::max(); }
    /// @}

    /// The first block at once: a walk always draws, and its Philox rounds then overlap whatever comes before.
    WalkRng(std::uint64_t seed, std::uint64_t cell, std::uint64_t walk) : key_{{seed, cell}}, ctr_{{walk, 0, 0, 0}} {
        block_ = r123::Philox4x64()(ctr_, key_);
        ++ctr_.v[1];
    }

    /// Small enough to inline where it is called (a sampler keeps its registers); the next block, every 4 numbers, is
    /// out of line.
    result_type operator()() {
        if (next_ == 4) [[unlikely]]
            refill();
        return block_.v[next_++];
    }

private:
    [[gnu::noinline]] void refill() {
        block_ = r123::Philox4x64()(ctr_, key_);
        ++ctr_.v[1];
        next_ = 0;
    }

    r123::Philox4x64::key_type key_;
    r123::Philox4x64::ctr_type ctr_;
    r123::Philox4x64::ctr_type block_;
    int next_ = 0;
};

/// Uniform in [0, 1): the top 53 bits, so every value is a multiple of 2^-53 and 1 is never returned. Always inlined
/// (with WalkRng: a load, a shift, a conversion).
template <class G>
requires std::uniform_random_bit_generator<G> &&(G::min() == 0) &&
    (G::max() == ~std::uint64_t{0}) [[gnu::always_inline]] inline double uniform01(G& g) {
    return static_cast<double>(g() >> 11) * 0x1.0p-53;
}

/// Two independent uniforms in (-1, 1) from one draw, a point of the square [-1, 1]^2: each half of the 64 bits, as
/// a signed 32-bit integer k, gives (k + 1/2) 2^-31, on a grid of step 2^-31 symmetric about 0 (a rejection sampler
/// of the unit disk draws one per try; detail/visible_normals_closed.hpp).
struct SquarePoint {
    /// The point's two coordinates, each in (-1, 1).
    /// @{
    double a, b;
    /// @}
};
/// The point of the square from one draw of g, as above.
template <class G>
requires std::uniform_random_bit_generator<G> &&(G::min() == 0) &&
    (G::max() == ~std::uint64_t{0}) [[gnu::always_inline]] inline SquarePoint uniform_square(G& g) {
    const std::uint64_t x = g();
    const auto hi = static_cast<std::int32_t>(static_cast<std::uint32_t>(x >> 32));
    const auto lo = static_cast<std::int32_t>(static_cast<std::uint32_t>(x));
    return {(static_cast<double>(hi) + 0.5) * 0x1.0p-31, (static_cast<double>(lo) + 0.5) * 0x1.0p-31};
}

}  // namespace smithlab
