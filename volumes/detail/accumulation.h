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
    glm::vec3 axisArea{0.0f};      // sum of clipped area * |unit normal| / h^2, per axis
    glm::vec3 albedoSum{0.0f};     // albedo weighted by area (+ a tiny weight for touch-only)
    float albedoWeight = 0.0f;

    VoxelSums& operator+=(const VoxelSums& s) {
        area += s.area;
        vectorArea += s.vectorArea;
        axisArea += s.axisArea;
        albedoSum += s.albedoSum;
        albedoWeight += s.albedoWeight;
        return *this;
    }
    // Every sum scaled (a coarser level's face is 4 finer faces).
    VoxelSums& operator*=(float k) {
        area *= k;
        vectorArea *= k;
        axisArea *= k;
        albedoSum *= k;
        albedoWeight *= k;
        return *this;
    }
};

// One leaf's sums by voxel offset while triangles (or finer voxels) are added to it. A scratch
// that the adding thread owns and reuses from leaf to leaf: pack() leaves it zero again.
struct DenseSums {
    VoxelSums voxel[512];
};

// A leaf's occupancy and, once packed, the sums of its active voxels only, in offset order:
// surfaces fill about a sixth of a leaf, so packed sums take a sixth of the 16 KiB a dense
// leaf would hold until the level is finished.
class AccumLeaf {
public:
    explicit AccumLeaf(const glm::ivec3& origin);
    ~AccumLeaf();

    static int offset(int x, int y, int z) { return ((x & 7) << 6) | ((y & 7) << 3) | (z & 7); }
    const glm::ivec3& origin() const { return origin_; }
    // Moves the leaf by whole leaves (bins rasterize in local coordinates).
    void translate(const glm::ivec3& delta);

    // Gathering: marks the voxel occupied and adds to its sums in `dense`.
    void add(int offset, const VoxelSums& s, DenseSums& dense) {
        leaf_->setValueOn(openvdb::Index(offset), true);
        dense.voxel[offset] += s;
    }
    // Keeps the active voxels' sums from `dense` and zeroes those entries of it.
    void pack(DenseSums& dense);
    // f(offset, sums) for every active voxel, in offset order (once packed).
    template <typename F>
    void forEachActive(F&& f) const {
        std::size_t i = 0;
        for (auto it = leaf_->cbeginValueOn(); it; ++it, ++i) f(int(it.pos()), packed_[i]);
    }

    // Hands the occupancy leaf to `tree` (it stays reachable for writeAttributes).
    void moveOccupancyInto(openvdb::BoolTree& tree);
    // Writes the final attributes of the active voxels from the leaf's transient data on (set by
    // indexLeaves), after any coarser level has read the sums.
    void writeAttributes(LevelGrids& level, BlockerFit fit) const;

private:
    glm::ivec3 origin_;
    OccupancyLeaf* leaf_;  // owned until moveOccupancyInto
    bool ownsLeaf_ = true;
    std::unique_ptr<VoxelSums[]> packed_;
};

using AccumLevel = std::vector<std::unique_ptr<AccumLeaf>>;

// Level L+1 from level L (not yet finished): sums added 2x2x2, areas rescaled to the coarser
// face area.
AccumLevel downsample(const AccumLevel& fine);

}  // namespace voxgi::detail
