#include "gi/lpv/cascades.h"

#include <algorithm>
#include <cmath>

namespace voxgi {

float finestCellSize(const LpvDesc& desc, const Bounds& b, glm::vec3 eye) {
    if (desc.cellSize > 0.0f) return desc.cellSize;
    glm::vec3 e = b.valid() ? b.extent() : glm::vec3(1.0f);
    // The scene plus a one-cell margin on each side.
    const float sceneFit = std::max({e.x, e.y, e.z, 1e-30f}) / float(desc.resolution - 2);
    if (desc.cascades == 1) return sceneFit;
    if (desc.cascadeBounds == CascadeBounds::Scene) return sceneFit / float(1 << (desc.cascades - 1));
    // Cascades: the coarsest level reaches the farthest corner of the scene from the camera.
    float farthest = 1e-30f;
    for (int i = 0; i < 8; ++i) {
        glm::vec3 corner((i & 1) ? b.max.x : b.min.x, (i & 2) ? b.max.y : b.min.y, (i & 4) ? b.max.z : b.min.z);
        farthest = std::max(farthest, glm::length(corner - eye));
    }
    return 2.0f * farthest / float(desc.resolution * (1 << (desc.cascades - 1)));
}

std::vector<CascadePlacement> placeCascades(const LpvDesc& desc, const Bounds& b, glm::vec3 eye,
                                            glm::vec3 viewDirection) {
    std::vector<CascadePlacement> out;
    const float h0 = finestCellSize(desc, b, eye);
    const int n = desc.resolution;
    for (int level = 0; level < desc.cascades; ++level) {
        CascadePlacement p;
        p.grid.resolution = n;
        p.grid.cellSize = h0 * float(1 << level);
        const float h = p.grid.cellSize;
        glm::vec3 center;
        if (desc.cascades == 1) {
            center = b.valid() ? b.center() : glm::vec3(0.0f);
        } else {
            glm::vec3 dir = glm::length(viewDirection) > 0.0f ? glm::normalize(viewDirection) : glm::vec3(0.0f);
            center = eye + dir * (desc.forwardOffset * float(n) * h);
        }
        const bool inScene = desc.cascades > 1 && desc.cascadeBounds == CascadeBounds::Scene && b.valid();
        if (inScene)
            for (int a = 0; a < 3; ++a) {
                // Inside the bounds with a cell to spare; a cascade wider than them sits at their centre.
                const float lo = b.min[a] + 0.5f * float(n - 2) * h, hi = b.max[a] - 0.5f * float(n - 2) * h;
                center[a] = lo > hi ? 0.5f * (b.min[a] + b.max[a]) : std::clamp(center[a], lo, hi);
            }
        glm::vec3 half(0.5f * float(n) * h);
        p.grid.origin = glm::ivec3(glm::floor((center - half) / h + 0.5f));
        // A volume holding the whole scene does not fade: nothing outside sends or receives light
        // (one fitted volume; in scene bounds, every cascade as wide as the scene).
        const bool wholeScene = desc.cascades == 1 || (inScene && glm::all(glm::lessThanEqual(p.grid.worldMin(), b.min)) &&
                                                       glm::all(glm::greaterThanEqual(p.grid.worldMax(), b.max)));
        p.fadeMin = wholeScene ? glm::vec3(-1e30f) : center - half;
        p.fadeMax = wholeScene ? glm::vec3(1e30f) : center + half;
        p.fadeWidth = wholeScene ? 0.0f : desc.fadeCells * h;
        out.push_back(p);
    }
    return out;
}

float cascadeInlier(const CascadePlacement& cascade, glm::vec3 x) {
    const CascadeGrid& g = cascade.grid;
    const glm::vec3 lo = g.worldMin(), hi = g.worldMax();
    if (x.x < lo.x || x.y < lo.y || x.z < lo.z || x.x > hi.x || x.y > hi.y || x.z > hi.z) return 0.0f;
    if (cascade.fadeWidth <= 0.0f) return 1.0f;
    const glm::vec3 d = glm::min(x - cascade.fadeMin, cascade.fadeMax - x);
    return std::clamp(std::min({d.x, d.y, d.z}) / cascade.fadeWidth, 0.0f, 1.0f);
}

SourceShares sourceShares(const std::vector<CascadePlacement>& cascades, std::size_t level, glm::vec3 x) {
    // outside = prod_{J < L} (1 - f_J(x)): the share of x not yet held by finer cascades.
    float outside = 1.0f;
    for (std::size_t j = 0; j < level && j < cascades.size() && outside > 0.0f; ++j)
        outside *= 1.0f - cascadeInlier(cascades[j], x);
    const float f = level < cascades.size() ? cascadeInlier(cascades[level], x) : 0.0f;
    return {outside * f, 1.0f - outside};
}

}  // namespace voxgi
