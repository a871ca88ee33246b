#include "gi/lpv/light_volume.h"

#include <algorithm>
#include <cmath>

#include "gi/sh/sh.h"

namespace voxgi {

void LightVolume::reset(const CascadeGrid& placement) {
    grid = placement;
    r.assign(grid.cellCount(), glm::vec4(0.0f));
    g.assign(grid.cellCount(), glm::vec4(0.0f));
    b.assign(grid.cellCount(), glm::vec4(0.0f));
}

void LightVolume::clear() {
    std::fill(r.begin(), r.end(), glm::vec4(0.0f));
    std::fill(g.begin(), g.end(), glm::vec4(0.0f));
    std::fill(b.begin(), b.end(), glm::vec4(0.0f));
}

bool LightVolume::isZero(std::size_t i) const {
    return r[i] == glm::vec4(0.0f) && g[i] == glm::vec4(0.0f) && b[i] == glm::vec4(0.0f);
}

void BlockerVolume::reset(const CascadeGrid& placement) {
    grid = placement;
    std::size_t n = std::size_t(cornerCount());
    blocker.assign(n * n * n, glm::vec4(0.0f));
    albedo.assign(n * n * n, glm::vec3(0.0f));
}

float blockerPeak(glm::vec4 b) {
    return b.x * sh::kY00 + std::sqrt(b.y * b.y + b.z * b.z + b.w * b.w) * sh::kY1;
}

glm::vec4 mergeBlockers(glm::vec4 a, glm::vec4 b) {
    // Two sources facing the same way most likely saw the same surface: keep the stronger
    // (max, seed 000) so it is not counted twice. Facing opposite ways (band-1 vectors
    // disagree) they saw the two sides of a wall: both block, so add them. "Stronger" is the
    // larger peak: a plane's blocker from the voxelizer has no constant term (it blocks
    // exactly <n.w>_+, volumes/blocker_sh.h), so comparing Y00 alone dropped every planar
    // static blocker merged into an empty sample.
    glm::vec3 da(a.y, a.z, a.w), db(b.y, b.z, b.w);
    if (glm::dot(da, db) < 0.0f) return a + b;
    return blockerPeak(b) > blockerPeak(a) ? b : a;
}

void BlockerVolume::mergeMax(const BlockerVolume& other) {
    for (std::size_t i = 0; i < blocker.size(); ++i) {
        blocker[i] = mergeBlockers(blocker[i], other.blocker[i]);
        albedo[i] = glm::max(albedo[i], other.albedo[i]);
    }
}

}  // namespace voxgi
