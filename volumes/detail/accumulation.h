// Per-voxel sums gathered while voxelizing, kept directly in the OpenVDB leaves they end up in
// (no second copy of the volume): until a level is finalized the albedo leaf holds the weighted
// albedo sum, blocker leaf 0 the clipped area and blocker leaf 1 the albedo weight. Areas are in
// units of the level's voxel face area (index units).
#pragma once

#include <memory>
#include <vector>

#include <glm/glm.hpp>
#include <openvdb/openvdb.h>

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

    static int offset(int x, int y, int z) { return ((x & 7) << 6) | ((y & 7) << 3) | (z & 7); }
    const glm::ivec3& origin() const { return origin_; }
    // Moves the leaf by whole leaves (bins rasterize in local coordinates).
    void translate(const glm::ivec3& delta);

    bool on(int offset) const { return occupancy_->isValueOn(openvdb::Index(offset)); }
    void add(int offset, const VoxelSums& s);
    VoxelSums sums(int offset) const;

    // Turns the sums into the final values (after any coarser level has read them), then
    // hands the leaves over to the level's grids.
    void finalizeValues(BlockerFit fit);
    void moveInto(LevelGrids& grids);

private:
    glm::ivec3 origin_;
    std::unique_ptr<openvdb::BoolTree::LeafNodeType> occupancy_;
    std::unique_ptr<openvdb::Vec3fTree::LeafNodeType> albedo_;
    std::unique_ptr<openvdb::Vec3fTree::LeafNodeType> normal_;
    std::unique_ptr<openvdb::FloatTree::LeafNodeType> blocker_[4];
};

using AccumLevel = std::vector<std::unique_ptr<AccumLeaf>>;

// Level L+1 from level L (not yet finalized): sums added 2x2x2, areas rescaled to the coarser
// face area.
AccumLevel downsample(const AccumLevel& fine);

}  // namespace voxgi::detail
