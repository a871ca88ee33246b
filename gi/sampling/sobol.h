// Sobol points and Owen scrambling for every sampler that wants stratified, randomised points
// (the path tracer's gi/pathtrace/sampler.h).
#pragma once

#include <cstdint>

namespace voxgi {

// The first kSobolDimensions coordinates of the Sobol sequence (Joe and Kuo's primitive
// polynomials and initial direction numbers), as 32-bit fixed point in [0, 1).
constexpr int kSobolDimensions = 4;
std::uint32_t sobol(std::uint32_t index, int dimension);

// Nested uniform scrambling of the bits of x from the most significant down, keyed by seed: a
// bijection in which bit k's flip depends only on the bits above it (so a stratum of the unit
// interval maps onto a stratum of the same size).
std::uint32_t nestedUniformScramble(std::uint32_t x, std::uint32_t seed);

// The same in bit-reversed form, the form Owen scrambling works in: sobolReversed(reverse(i), d)
// == reverse(sobol(i, d)), and nestedUniformScramble(x, s) == reverse(owenPermutationReversed(
// reverse(x), s)). Samplers that chain them reverse bits once, at the end. Inline: the path
// tracer calls them several times per decision, and a call each cost it 5 % of its time.
inline std::uint32_t reverseBits(std::uint32_t x) {
    x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
    x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
    x = ((x >> 4) & 0x0F0F0F0Fu) | ((x & 0x0F0F0F0Fu) << 4);
    return __builtin_bswap32(x);
}

// The generator matrices in bit-reversed form, applied a byte of the reversed index at a time:
// kSobolReversedTables.t[d][byte][value] is the reversed xor of the direction numbers that the
// set bits of `value` select there (reversed bit j is the index's bit 31 - j). 16 KiB in all.
struct SobolReversedTables {
    std::uint32_t t[kSobolDimensions][4][256];
};
extern const SobolReversedTables kSobolReversedTables;

inline std::uint32_t sobolReversed(std::uint32_t reversedIndex, int dimension) {
    const auto& t = kSobolReversedTables.t[dimension];
    return t[0][reversedIndex & 0xFFu] ^ t[1][(reversedIndex >> 8) & 0xFFu] ^ t[2][(reversedIndex >> 16) & 0xFFu] ^
           t[3][reversedIndex >> 24];
}

inline std::uint32_t owenPermutationReversed(std::uint32_t x, std::uint32_t seed) {
    // Every step changes a bit only as a function of the bits below it (addition, and xor with
    // a product by an even constant): in reversed order that is exactly Owen's nesting, each
    // digit flipped by a function of the digits above it (Laine and Karras 2011; the
    // multipliers are Vegdahl's, which pass the avalanche tests).
    x += seed;
    x ^= x * 0x6c50b47cu;
    x ^= x * 0xb82f1e52u;
    x ^= x * 0xc7afe638u;
    x ^= x * 0x8d22f6e6u;
    return x;
}

}  // namespace voxgi
