#include "gi/lpv/light_volume.h"

#include <algorithm>

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

void GeometryVolume::reset(const CascadeGrid& placement) {
    grid = placement;
    std::size_t n = std::size_t(cornerCount());
    blocker.assign(n * n * n, glm::vec4(0.0f));
    albedo.assign(n * n * n, glm::vec3(0.0f));
}

void GeometryVolume::mergeMax(const GeometryVolume& other) {
    // The max is taken on the blocker's mean (the Y00 coefficient) and the winner's whole SH
    // vector is kept: a per-coefficient max of signed band-1 terms would invent directions.
    for (std::size_t i = 0; i < blocker.size(); ++i) {
        if (other.blocker[i].x > blocker[i].x) blocker[i] = other.blocker[i];
        albedo[i] = glm::max(albedo[i], other.albedo[i]);
    }
}

}  // namespace voxgi
