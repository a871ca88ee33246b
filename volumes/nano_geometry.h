// A geometry volume level as NanoVDB grids in one buffer, for GPU ray casting through the
// occupancy (shaders/common/nano_geometry.glsl reads it with PNanoVDB.h). Two Vec3f grids over
// the occupied voxels: the mean normal, its length the voxel's consistency |sum a n| / sum a
// (1 for surfaces all facing one way, near 0 for the two faces of a thin wall or a column's
// faces all round), and the diffuse albedo; optionally a float grid of where the surface lies
// in each voxel. Voxel (i, j, k) covers [i, i+1] x [j, j+1] x [k, k+1] * voxelSize in world
// space, so a world point p lies in voxel floor(p / voxelSize).
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include <glm/glm.hpp>

namespace voxgi {

class SparseGeometryVolume;

struct NanoGeometry {
    std::vector<std::uint32_t> words;  // the grids, each starting on a 32-byte boundary
    std::uint32_t normalGrid = 0;      // byte offsets of the grids in `words`
    std::uint32_t albedoGrid = 0;
    std::uint32_t offsetGrid = 0;      // 0: no surface offsets
    float voxelSize = 0.0f;
    std::uint64_t activeVoxels = 0;

    std::uint64_t bytes() const { return words.size() * sizeof(std::uint32_t); }
};

// What the source geometry says about an occupied voxel's surface (centre and unit mean
// normal given): the signed distance s from the centre along the normal to the surface (it
// passes through centre + s n), and the albedo a ray arriving along -n sees, when one was seen
// (it replaces the area mean: a black light quad 0.8 mm in front of a white ceiling shares its
// voxels, and the area mean makes both grey). Called from several threads.
struct VoxelSurface {
    float offset = 0.0f;
    glm::vec3 albedo{0.0f};
    bool albedoSeen = false;
};
using SurfaceProbe = std::function<VoxelSurface(glm::vec3 centre, glm::vec3 normal)>;

// Peak bytes makeNanoGeometry needs for `level` (the buffer, and one grid's OpenVDB copy and
// NanoVDB handle while it is converted), from the occupancy's node counts.
double nanoGeometryBytes(const SparseGeometryVolume& volume, int level = 0, bool surfaceOffsets = true);

// The grids of `level`: mean normal (coverage) and albedo as Vec3f and, given `surfaceProbe`,
// the offsets as a float grid and the albedo it saw. Throws InputError when nanoGeometryBytes exceeds the memory
// limit (scenes/memory_limit.h), before building, and when the buffer would pass 4 GiB (32-bit
// addresses).
NanoGeometry makeNanoGeometry(const SparseGeometryVolume& volume, int level = 0,
                              const SurfaceProbe& surfaceProbe = {});

}  // namespace voxgi
