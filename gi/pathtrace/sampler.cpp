#include "gi/pathtrace/sampler.h"

#include "gi/sampling/hash.h"
#include "gi/sampling/sobol.h"

namespace voxgi::pt {

PathSampler::PathSampler(std::uint64_t seed, std::uint64_t pixel, std::uint64_t sample)
    // Samples past 2^32 of one pixel (never reached in practice) start a new pattern.
    : pixelKey_(std::uint32_t(mix64(seed ^ mix64(pixel ^ mix64((sample >> 32) + 0x9E3779B97F4A7C15ull))))), reversedIndex_(reverseBits(std::uint32_t(sample))) {}

glm::vec3 PathSampler::point(std::uint32_t decision, int dimensions) const {
    const std::uint32_t key = hash32(pixelKey_ ^ hash32(decision + 0x68E31DA4u));
    // Shuffling the index within aligned power-of-two blocks (a nested uniform scramble of it)
    // keeps each block a net while decorrelating this decision's pattern from every other's.
    // All in bit-reversed form: one reversal per coordinate, at the end.
    const std::uint32_t shuffled = owenPermutationReversed(reversedIndex_, key);
    glm::vec3 p(0.0f);
    for (int d = 0; d < dimensions; ++d) {
        const std::uint32_t x = reverseBits(
            owenPermutationReversed(sobolReversed(shuffled, d), hash32(key + 0x9E3779B9u * std::uint32_t(d + 1))));
        p[d] = float(x >> 8) * (1.0f / 16777216.0f);  // 24 bits: strictly below one in float
    }
    return p;
}

}  // namespace voxgi::pt
