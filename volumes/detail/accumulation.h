// Per-voxel sums gathered while voxelizing: the occupancy leaf that ends up in the level's
// topology plus dense sum arrays that live only until the level is finished (a coarser level
// reads them first). Areas are in units of the level's voxel face area (index units).
#pragma once

#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "volumes/detail/geometry_grids.h"

namespace voxgi::detail {

struct VoxelSums {
    float area = 0.0f;             // clipped triangle area / h^2
    glm::vec3 vectorArea{0.0f};    // sum of clipped area * unit normal / h^2
    glm::vec3 albedoSum{0.0f};     // albedo weighted by area (+ a tiny weight for touch-only)
    float albedoWeight = 0.0f;
};

class AccumLeaf {
public:
    explicit AccumLeaf(const glm::ivec3& origin);
    ~AccumLeaf();

    static int offset(int x, int y, int z) { return ((x & 7) << 6) | ((y & 7) << 3) | (z & 7); }
    const glm::ivec3& origin() const { return origin_; }
    // Moves the leaf by whole leaves (bins rasterize in local coordinates).
    void translate(const glm::ivec3& delta);

    bool on(int offset) const { return leaf_->isValueOn(openvdb::Index(offset)); }
    void add(int offset, const VoxelSums& s);
    VoxelSums sums(int offset) const;

    // Hands the occupancy leaf to `tree` (it stays reachable for writeAttributes).
    void moveOccupancyInto(openvdb::BoolTree& tree);
    // Writes the final attributes of the active voxels from the leaf's transient data on (set by
    // indexLeaves), after any coarser level has read the sums.
    void writeAttributes(LevelGrids& level, BlockerFit fit) const;

private:
    struct DenseSums {
        float area[512];
        float albedoWeight[512];
        glm::vec3 vectorArea[512];
        glm::vec3 albedoSum[512];
    };
    glm::ivec3 origin_;
    OccupancyLeaf* leaf_;  // owned until moveOccupancyInto
    bool ownsLeaf_ = true;
    std::unique_ptr<DenseSums> sums_;
};

using AccumLevel = std::vector<std::unique_ptr<AccumLeaf>>;

// Level L+1 from level L (not yet finished): sums added 2x2x2, areas rescaled to the coarser
// face area.
AccumLevel downsample(const AccumLevel& fine);

}  // namespace voxgi::detail
