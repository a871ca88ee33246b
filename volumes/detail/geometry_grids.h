// The storage behind SparseGeometryVolume, for .cpp files only (never include from a public header).
//
// In memory a level is compact: the occupancy BoolGrid is the topology, and the attributes live
// in arrays holding the ACTIVE voxels only (OpenVDB leaves are dense, 512 values whatever the
// active count, and Sponza's leaves are ~15% full). Each occupancy leaf's transient data is the
// array index of its first active voxel; the leaf's other active voxels follow in leaf offset
// order, so a voxel's index is that base plus the active bits of the leaf mask below it (the
// scheme of NanoVDB's OnIndex grids). Files hold ordinary dense OpenVDB grids: expandGrids()
// builds them for writing, compactLevel() turns them back into this form when reading.
//
// Storage per active voxel (docs/volumes.md): normal (vector coverage) and the blocker's constant
// SH coefficient c0 as floats, exactly as computed; the linear blocker coefficients c1..c3 are
// the normal times a constant (blockerSH), so they are not stored; albedo and the projected
// coverage as three IEEE half floats each (relative error <= 2^-11, see toHalves).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <openvdb/openvdb.h>

#include "volumes/geometry_volume.h"

namespace voxgi::detail {

using OccupancyLeaf = openvdb::BoolTree::LeafNodeType;
using Half3 = std::array<openvdb::math::half, 3>;

struct LevelGrids {
    double voxelSize = 0.0;
    openvdb::BoolGrid::Ptr occupancy;   // leaves only (no active tiles); transient data = first index
    std::vector<glm::vec4> normalC0;    // xyz: normal (vector coverage), w: blocker SH c0
    std::vector<Half3> albedo;
    std::vector<Half3> projected;       // projected coverage per axis (SparseGeometryVolume::projectedCoverage)

    // Attribute index of voxel ijk, or -1 when it is not occupied.
    std::int64_t attributeIndex(const openvdb::Coord& ijk) const;
    // Tree, offsets (in the leaves) and attribute arrays by capacity.
    std::uint64_t memoryBytes() const;
};

struct GeometryGrids {
    std::vector<LevelGrids> levels;
    openvdb::FloatGrid::Ptr sdf;  // level 0, optional
    std::string sourceHash;
    BlockerFit blockerFit = BlockerFit::PlaneExact;
    VoxelizeStats stats;
};

// Voxel (i, j, k) covers [i, i+1] * h in world space: centres at (i + 0.5) * h.
openvdb::math::Transform::Ptr voxelTransform(double voxelSize);

// Three floats to halves: clamped to the finite half range [-65504, 65504], then rounded to
// nearest, so |stored - value| <= 2^-11 |value| for |value| >= 2^-14 and <= 2^-25 below.
Half3 toHalves(const glm::vec3& value);
glm::vec3 fromHalves(const Half3& value);

// Sets each leaf's transient data to the running count of active voxels before it (leaf order)
// and returns the total. Throws InputError when a leaf would start past 2^32 - 1.
std::uint64_t indexLeaves(openvdb::BoolTree& tree);

// The grids a .vdb file holds, in file order: per level occupancy (sharing the in-memory tree),
// albedo, normal, blocker_sh0..3, projected_coverage as dense OpenVDB grids; then sdf. Named, classed and annotated
// with voxgi metadata.
openvdb::GridPtrVec expandGrids(const GeometryGrids& grids);

// A level from its file grids (occupancy is taken over; its active tiles are voxelized). The
// blocker's c1..c3 must agree with the normal grid (voxgi writes them from it); a file where
// they do not is refused with an InputError naming `path`.
// A file without a projected_coverage grid (written before it existed) gets the estimate
// isotropicProjectedCoverage (volumes/blocker_sh.h) from its blocker and normal.
struct LevelFileGrids {
    openvdb::BoolGrid::Ptr occupancy;
    openvdb::Vec3fGrid::ConstPtr albedo, normal, projected;  // projected may be null
    std::array<openvdb::FloatGrid::ConstPtr, 4> blocker;
};
LevelGrids compactLevel(LevelFileGrids&& grids, BlockerFit fit, const std::string& path);

}  // namespace voxgi::detail
