// Per-voxel sums gathered while voxelizing, in 8^3 leaves laid out like OpenVDB leaves, before
// they become grids. Areas are in units of the level's voxel face area (index units).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

namespace voxgi::detail {

struct VoxelSums {
    float area = 0.0f;             // clipped triangle area / h^2
    glm::vec3 vectorArea{0.0f};    // sum of clipped area * unit normal / h^2
    glm::vec3 albedoSum{0.0f};     // albedo weighted by area (+ a tiny weight for touch-only)
    float albedoWeight = 0.0f;
};

struct AccumLeaf {
    glm::ivec3 origin{0};          // multiple of 8, index space of its level
    std::uint64_t mask[8] = {};    // occupancy bits, OpenVDB offset order
    VoxelSums voxels[512];

    static int offset(int x, int y, int z) { return ((x & 7) << 6) | ((y & 7) << 3) | (z & 7); }
    void touch(int offset) { mask[offset >> 6] |= std::uint64_t(1) << (offset & 63); }
    bool on(int offset) const { return (mask[offset >> 6] >> (offset & 63)) & 1u; }
};

using AccumLevel = std::vector<std::unique_ptr<AccumLeaf>>;

// Level L+1 from level L: voxel sums added 2x2x2, areas rescaled to the coarser face area.
AccumLevel downsample(const AccumLevel& fine);

}  // namespace voxgi::detail
