// The path tracer's sample points: Owen-scrambled Sobol points, one small Sobol pattern per
// decision of a path (pixel position, light sample, BSDF sample, roulette), each randomised on
// its own. Burley's 2020 construction: a decision's point is the Sobol point at a per-pixel,
// per-decision shuffled index, its coordinates scrambled with nested uniform (Owen) scrambling
// by a per-pixel, per-decision, per-coordinate hash. So within a decision the first 2^k samples
// of a pixel are a stratified (0, k, 2)-net in its first two coordinates, and decisions stay
// independent of each other. The points depend on (seed, pixel, sample index) only: any thread
// count gives the same image.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

namespace voxgi::pt {

// Decisions are numbered by the caller (pixel position 0, then fixed slots per bounce), so
// the k-th bounce's BSDF sample of every path of a pixel comes from one pattern even when some
// paths skipped a decision before it.
class PathSampler {
public:
    PathSampler(std::uint64_t seed, std::uint64_t pixel, std::uint64_t sample);

    float get1D(std::uint32_t decision) const { return point(decision, 1).x; }
    glm::vec2 get2D(std::uint32_t decision) const {
        glm::vec3 p = point(decision, 2);
        return {p.x, p.y};
    }
    glm::vec3 get3D(std::uint32_t decision) const { return point(decision, 3); }

private:
    glm::vec3 point(std::uint32_t decision, int dimensions) const;
    std::uint32_t pixelKey_;
    std::uint32_t reversedIndex_;  // the sample index, bits reversed
};

}  // namespace voxgi::pt
