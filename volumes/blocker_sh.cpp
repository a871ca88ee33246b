// Derivation of the blocker coefficients.
//
// Seeds 000 (CLPV, §3.10.2, eq. 3.4) and 001 (ILPV, §3.2.1) give each surface element p in a
// cell the blocking distribution B_p(w) = W_p <n_p . w>_+ with the weight W_p = A_s / A_c
// (surfel area over the area of a cell face), projected to SH and summed over the cell. Here the
// surface elements are the exact pieces of the triangles clipped to the voxel box, so with
// S = sum_p W_p (coverage) and m = sum_p W_p n_p (vector coverage) the summed function is
//   F(w) = sum_p W_p <n_p . w>_+ .
// For a closed object F(w) is its silhouette area seen from w over the face area, and for one
// wall crossing the voxel along an axis W = 1 and F(w) = <n . w>_+ : fully blocking along n.
//
// Two bands hold only a constant plus a linear term, a + b . w:
// * Projection (the seeds' literal L2 projection): the clamped cosine <n . w>_+ projects to
//   1/4 + (n . w)/2, so F ~ S/4 + m.w/2. A full wall then blocks 0.75 along its normal and 0.25
//   along its own plane.
// * PlaneExact (default): the constant term must be S/4 for a closed object (by Cauchy's
//   formula the mean silhouette of a convex body is a quarter of its area, and m = 0), and
//   should vanish for a single plane (|m| = S), where the exact answer is the linear
//   function m . w clamped. a = (S - |m|)/4, b = m meets both: a closed object blocks
//   isotropically with its mean silhouette, a wall blocks exactly <n . w>_+ (1 along n, 0 in its
//   plane, 0 behind it after the clamp), and mixtures fall in between. S and m are additive,
//   so coarser cascade levels are built from summed fine voxels with the same rule.
// In both fits the SH coefficients follow from a = c0 Y00 and b . w = c1 Y1-1 + c2 Y10 + c3 Y11.
#include "volumes/blocker_sh.h"

#include <algorithm>
#include <cmath>

namespace voxgi {

glm::vec4 blockerFromCoverage(float coverage, const glm::vec3& vectorCoverage, BlockerFit fit) {
    // |m| <= S holds exactly; rounding may break it by an ulp.
    const float constant = fit == BlockerFit::Projection ? 0.25f * coverage
                                                         : 0.25f * std::max(0.0f, coverage - glm::length(vectorCoverage));
    return blockerSH(constant / kShY00, vectorCoverage, fit);
}

float coverageFromBlocker(float c0, const glm::vec3& vectorCoverage, BlockerFit fit) {
    const float constant = 4.0f * kShY00 * c0;
    return fit == BlockerFit::Projection ? constant : constant + glm::length(vectorCoverage);
}

glm::vec3 isotropicProjectedCoverage(float coverage, const glm::vec3& vectorCoverage) {
    return glm::abs(vectorCoverage) + 0.5f * std::max(0.0f, coverage - glm::length(vectorCoverage));
}

glm::vec4 blockerSH(float c0, const glm::vec3& vectorCoverage, BlockerFit fit) {
    const glm::vec3 linear = fit == BlockerFit::Projection ? 0.5f * vectorCoverage : vectorCoverage;
    return glm::vec4(c0, -linear.y / kShY1, linear.z / kShY1, -linear.x / kShY1);
}

float evaluateBlocker(const glm::vec4& sh, const glm::vec3& w) {
    float b = sh[0] * kShY00 - sh[1] * kShY1 * w.y + sh[2] * kShY1 * w.z - sh[3] * kShY1 * w.x;
    return std::clamp(b, 0.0f, 1.0f);
}

const char* blockerFitName(BlockerFit fit) {
    return fit == BlockerFit::Projection ? "projection" : "plane-exact";
}

}  // namespace voxgi
