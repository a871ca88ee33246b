// The volumes of one cascade: the light volume (per cell, the intensity distribution of a
// virtual point light at the cell centre, W/sr, as 2-band SH per colour) and the geometry
// volume (blocker SH and albedo) whose samples sit at the light volume's cell corners, i.e.
// shifted by half a cell (seed 000 section 3.10.1).
#pragma once

#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

namespace voxgi {

// Placement of a cascade: cell (i, j, k) spans world [(origin + ijk) h, (origin + ijk + 1) h].
struct CascadeGrid {
    glm::ivec3 origin{0};  // world cell index of the first cell (cells snap to multiples of h)
    int resolution = 32;
    float cellSize = 1.0f;

    glm::vec3 worldMin() const { return glm::vec3(origin) * cellSize; }
    glm::vec3 worldMax() const { return glm::vec3(origin + glm::ivec3(resolution)) * cellSize; }
    glm::vec3 cellCenter(glm::ivec3 local) const { return (glm::vec3(origin + local) + 0.5f) * cellSize; }
    std::size_t cellCount() const { return std::size_t(resolution) * std::size_t(resolution) * std::size_t(resolution); }
    bool contains(glm::ivec3 local) const {
        return local.x >= 0 && local.y >= 0 && local.z >= 0 && local.x < resolution && local.y < resolution &&
               local.z < resolution;
    }
    std::size_t index(glm::ivec3 local) const {
        return (std::size_t(local.z) * std::size_t(resolution) + std::size_t(local.y)) * std::size_t(resolution) +
               std::size_t(local.x);
    }
    // Local cell containing a world point (may be outside the grid).
    glm::ivec3 cellOf(glm::vec3 p) const { return glm::ivec3(glm::floor(p / cellSize)) - origin; }
};

// SH4 per colour channel, stored as vec4 (x = Y00, y = Y1-1, z = Y10, w = Y11) like the GL
// RGBA32F textures, so uploads are plain copies.
struct LightVolume {
    CascadeGrid grid;
    std::vector<glm::vec4> r, g, b;

    void reset(const CascadeGrid& placement);
    void clear();
    bool isZero(std::size_t i) const;
};

// Blocker SH (probability that light travelling in a direction is stopped) and diffuse albedo
// at the (resolution + 1)^3 cell corners.
struct BlockerVolume {
    CascadeGrid grid;
    std::vector<glm::vec4> blocker;
    std::vector<glm::vec3> albedo;

    void reset(const CascadeGrid& placement);
    int cornerCount() const { return grid.resolution + 1; }
    std::size_t cornerIndex(glm::ivec3 c) const {
        std::size_t n = std::size_t(cornerCount());
        return (std::size_t(c.z) * n + std::size_t(c.y)) * n + std::size_t(c.x);
    }
    // Merges another source (mergeBlockers per sample; albedo by max per channel).
    void mergeMax(const BlockerVolume& other);
};

// The merge of two sources' blockers at one sample: the one with the larger peak
// (blockerPeak) when they face the same way, the sum when they face opposite ways (the two
// sides of one wall).
glm::vec4 mergeBlockers(glm::vec4 a, glm::vec4 b);
// The largest value of the blocker's 2-band function over directions: Y00 c0 + Y1 |c1|.
float blockerPeak(glm::vec4 b);

}  // namespace voxgi
