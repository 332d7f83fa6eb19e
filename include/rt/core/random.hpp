// random.hpp - a small explicit random number generator, seeded per pixel.
//
// rt never uses rand() or any global generator: every random number comes from
// a pcg32 object that the caller owns, seeded from (seed, pixel, sample). So a
// pixel's random numbers do not depend on which thread or tile computes it, or
// on what was computed before: the image is the same for any thread count.
//
// PCG32 ("XSH RR" output on a 64-bit linear congruential state): M. E. O'Neill,
// "PCG: A Family of Simple Fast Space-Efficient Statistically Good Algorithms
// for Random Number Generation", Harvey Mudd College HMC-CS-2014-0905 (2014):
// the generator "pcg32" (PCG-XSH-RR 64/32), with the LCG multiplier
// 6364136223846793005 and the seeding of her reference implementation
// (pcg-random.org, pcg32_srandom_r):
//     state' = state * 6364136223846793005 + inc            (inc odd: the stream)
//     output = rotr32(((state >> 18) ^ state) >> 27, state >> 59)
// computed from the state before the step.
//
// Seeds are mixed with the SplitMix64 finaliser (G. L. Steele, D. Lea,
// C. H. Flood, "Fast Splittable Pseudorandom Number Generators", OOPSLA 2014;
// constants of D. Stafford's "Mix13"), so that neighbouring pixel indices give
// unrelated generator states.
#pragma once

#include <cstdint>

namespace rt {

namespace detail {

/// SplitMix64's finaliser: a bijection of 64-bit words that mixes every input bit into every output bit.
inline std::uint64_t mix64(std::uint64_t z)
{
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

} // namespace detail

/// PCG32 (O'Neill 2014): 64 bits of state, 32-bit outputs, period 2^64 on each of 2^63 streams.
class pcg32 {
public:
    /// The generator of pcg32(0, 0).
    pcg32() : pcg32(0, 0) {}

    /// The reference seeding: `initstate` picks the start, `initseq` the stream.
    pcg32(std::uint64_t initstate, std::uint64_t initseq) : inc_((initseq << 1u) | 1u)
    {
        next_u32();
        state_ += initstate;
        next_u32();
    }

    /// The next 32 random bits.
    std::uint32_t next_u32()
    {
        const std::uint64_t old = state_;
        state_ = old * 6364136223846793005ull + inc_;
        const auto xorshifted = std::uint32_t(((old >> 18u) ^ old) >> 27u);
        const auto rot = std::uint32_t(old >> 59u);
        return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
    }

    /// A uniform float in [0, 1): the top 24 bits times 2^-24, so every value is
    /// exactly representable and 1 is never returned.
    float next_float() { return float(next_u32() >> 8) * (1.0f / 16777216.0f); }

    /// A uniform integer in [0, bound), bound >= 1, without modulo bias
    /// (rejection of the lowest 2^32 mod bound values).
    std::uint32_t next_below(std::uint32_t bound)
    {
        const std::uint32_t threshold = (0u - bound) % bound;
        for (;;) {
            const std::uint32_t r = next_u32();
            if (r >= threshold)
                return r % bound;
        }
    }

private:
    std::uint64_t state_ = 0;
    std::uint64_t inc_;
};

/// The generator of one purpose (`stream`) for pixel `pixel_index` and sample
/// `sample_index` of a render with `seed`: a pure function of the four numbers.
inline pcg32 seeded_generator(std::uint64_t seed, std::uint64_t pixel_index, std::uint64_t sample_index,
                              std::uint64_t stream)
{
    const std::uint64_t state = detail::mix64(detail::mix64(detail::mix64(seed) ^ pixel_index) ^ (sample_index * 0x9e3779b97f4a7c15ull));
    return pcg32(state, stream);
}

} // namespace rt
