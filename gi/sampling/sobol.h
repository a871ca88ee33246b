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
// reverse(x), s)). Samplers that chain them reverse bits once, at the end.
std::uint32_t reverseBits(std::uint32_t x);
std::uint32_t sobolReversed(std::uint32_t reversedIndex, int dimension);
std::uint32_t owenPermutationReversed(std::uint32_t x, std::uint32_t seed);

}  // namespace voxgi
