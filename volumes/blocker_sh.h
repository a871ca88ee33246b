// The blocker: how much of the light crossing a voxel in direction w the surfaces inside it
// stop, as 2-band real spherical harmonics (4 floats per voxel).
//
// Convention (shared with gi/lpv): B(w) = sum_i c_i Y_i(w), clamped to [0, 1], with
//   Y0 = Y00  =  0.282094792
//   Y1 = Y1-1 = -0.488602512 * w.y
//   Y2 = Y10  =  0.488602512 * w.z
//   Y3 = Y11  = -0.488602512 * w.x
// and coefficients stored in the order (c0, c1, c2, c3). w is the direction the blocked light
// comes FROM as seen from the voxel (CLPV evaluates beta = B(-w_propagation)); a front face
// (counter-clockwise winding, normal cross(b-a, c-a)) blocks light arriving on its front.
#pragma once

#include <glm/glm.hpp>

namespace voxgi {

inline constexpr float kShY00 = 0.282094792f;
inline constexpr float kShY1 = 0.488602512f;

// How the per-voxel blocking function is fitted into 2 bands (see blocker_sh.cpp).
enum class BlockerFit {
    PlaneExact,   // default: a single plane blocks exactly <n.w>_+ scaled by its coverage
    Projection,   // the seeds' literal L2 projection of each surfel's clamped cosine lobe
};

// `coverage` = sum of clipped triangle areas / voxel face area (the seeds' W = A_s / A_c);
// `vectorCoverage` = sum of clipped area * unit normal / voxel face area.
glm::vec4 blockerFromCoverage(float coverage, const glm::vec3& vectorCoverage, BlockerFit fit);

// The full coefficient vector from c0 and the vector coverage: c1..c3 depend on the vector
// coverage alone, which is why the geometry volumes store only c0 and the normal.
// blockerFromCoverage(S, m, fit) == blockerSH(blockerFromCoverage(S, m, fit)[0], m, fit) exactly.
glm::vec4 blockerSH(float c0, const glm::vec3& vectorCoverage, BlockerFit fit);

// The coverage S back from a stored c0 and the vector coverage (the inverse of
// blockerFromCoverage's c0, up to rounding).
float coverageFromBlocker(float c0, const glm::vec3& vectorCoverage, BlockerFit fit);

// The projected coverage P (sum of clipped area * |n_a| / voxel face area, per axis a) of
// surfaces known only by S and m: the part |m_a| of one orientation, plus the rest spread as if
// its normals pointed every way evenly (the mean |n_a| over the sphere is 1/2). Files written
// before the voxelizer stored P get this.
glm::vec3 isotropicProjectedCoverage(float coverage, const glm::vec3& vectorCoverage);

// B(w) with the convention above, clamped to [0, 1].
float evaluateBlocker(const glm::vec4& sh, const glm::vec3& w);

const char* blockerFitName(BlockerFit fit);

}  // namespace voxgi
