// Sparse geometry volumes: a scene's triangles voxelized into occupancy, albedo, normal and
// blocker SH, one set per cascade level, with .vdb I/O and a cache. In memory the occupancy is an
// OpenVDB tree and the attributes are compact arrays over its active voxels (albedo as halves,
// see docs/volumes.md for the layout and error bounds); files hold one standard OpenVDB grid per
// attribute. The storage stays behind a pimpl: volumes/detail/geometry_grids.h.
//
// Voxel (i, j, k) of level L is the closed box [i, i+1] x [j, j+1] x [k, k+1] * h_L in world
// space with h_L = voxelSize * 2^L, so voxel (i, j, k) of level L+1 holds voxels (2i..2i+1, ...)
// of level L. Bricks are OpenVDB leaves: 8^3 voxels with origins at multiples of 8.
//
// Blocker SH convention (gi/lpv reads it): B(w) = sum_i c_i Y_i(w) clamped to [0, 1],
// (c0, c1, c2, c3) = (Y00, Y1-1, Y10, Y11) with Y00 = 0.282094792, Y1-1 = -0.488602512 * y,
// Y10 = 0.488602512 * z, Y11 = -0.488602512 * x; w points from the voxel toward where the
// blocked light comes from (front faces block light arriving on their front). Files hold the
// four float grids blocker_sh0 .. blocker_sh3. See volumes/blocker_sh.{h,cpp} for the derivation.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scenes/scene.h"
#include "volumes/blocker_sh.h"

namespace voxgi {

namespace detail {
struct GeometryGrids;
}

// The smallest voxel edge OpenVDB's transforms accept (their scale determinant must stay above
// ~3e-15): voxelizeScene refuses smaller ones.
constexpr float kSmallestVoxelSize = 2e-5f;

struct VoxelizeSettings {
    float voxelSize = 0.1f;          // finest level, world units
    int levels = 1;                  // cascade levels, voxel size doubling per level
    std::uint64_t maxVoxels = 64ull << 20;  // refuse (InputError) when the estimate exceeds it
    bool sdf = false;                // also a narrow-band signed distance (watertight meshes)
    float sdfHalfWidth = 3.0f;       // in voxels
    BlockerFit blockerFit = BlockerFit::PlaneExact;
    // Called with the fraction done (0..1) from worker threads; may be empty.
    std::function<void(float)> progress;
};

struct VoxelizeStats {
    std::size_t triangles = 0;          // seen
    std::size_t trianglesUsed = 0;
    std::size_t skippedNonFinite = 0;   // NaN/Inf vertex
    std::size_t skippedDegenerate = 0;  // zero area, repeated or out-of-range index
    std::size_t overlapTests = 0;       // triangle-voxel pairs tested
    std::uint64_t estimatedVoxels = 0;  // the estimate checked against maxVoxels
    double seconds = 0.0;
};

// An active 8^3 brick: index-space origin (multiple of 8) and world bounds of its 8^3 voxels.
struct Brick {
    glm::ivec3 origin{0};
    glm::vec3 worldMin{0.0f};
    glm::vec3 worldMax{0.0f};
};

struct IndexBox {
    glm::ivec3 min{0};
    glm::ivec3 max{-1};  // inclusive; empty when any max < min
    bool empty() const { return max.x < min.x || max.y < min.y || max.z < min.z; }
};

// The sparse store; gi/lpv fills its dense per-cascade BlockerVolume from it.
class SparseGeometryVolume {
public:
    SparseGeometryVolume();
    ~SparseGeometryVolume();
    SparseGeometryVolume(SparseGeometryVolume&&) noexcept;
    SparseGeometryVolume& operator=(SparseGeometryVolume&&) noexcept;

    int levelCount() const;
    float voxelSize(int level = 0) const;
    bool hasSdf() const;
    const std::string& sourceHash() const;
    const VoxelizeStats& stats() const;

    bool occupied(const glm::ivec3& ijk, int level = 0) const;
    glm::vec4 blockerSH(const glm::ivec3& ijk, int level = 0) const;  // zero where empty
    // Area-weighted mean of the diffuse albedo (shaders/shared/material.h), linear; stored as
    // halves: |error| <= 2^-11 |albedo| (2^-25 below 2^-14).
    glm::vec3 albedo(const glm::ivec3& ijk, int level = 0) const;
    // Sum of clipped area * unit normal / voxel face area: direction = mean normal, length =
    // projected coverage (1 for a wall crossing the voxel along an axis).
    glm::vec3 normal(const glm::ivec3& ijk, int level = 0) const;
    // Per axis a, the sum of clipped area * |n_a| / voxel face area: the area of the surfaces seen
    // along the axis, every layer counted (a floor's 1 on y; a closed surface shows half of it,
    // each part seen from both sides; a vertical column none on y). Halves like albedo.
    glm::vec3 projectedCoverage(const glm::ivec3& ijk, int level = 0) const;
    float sdf(const glm::ivec3& ijk) const;  // level 0 only; background outside the band

    std::uint64_t activeVoxelCount(int level = 0) const;
    IndexBox indexBounds(int level = 0) const;
    glm::vec3 voxelCenter(const glm::ivec3& ijk, int level = 0) const;
    glm::ivec3 voxelAt(const glm::vec3& world, int level = 0) const;

    // Occupancy culling: the bricks holding an occupied voxel after dilating occupancy by
    // `dilateVoxels` (face-, edge- and vertex-neighbours), sorted by origin (z, then y, then x).
    std::vector<Brick> activeBricks(int level = 0, int dilateVoxels = 0) const;

    // Total bytes held in memory: occupancy trees (OpenVDB memUsage, leaf offsets included),
    // attribute arrays by capacity, the optional sdf grid.
    std::uint64_t memoryBytes() const;

    detail::GeometryGrids& grids();
    const detail::GeometryGrids& grids() const;

private:
    std::unique_ptr<detail::GeometryGrids> grids_;
};

// Voxelizes every mesh of the scene. Throws InputError on an unusable setting (voxel size,
// levels, estimated voxel count above maxVoxels). Bad triangles are skipped and counted.
SparseGeometryVolume voxelizeScene(const Scene& scene, const VoxelizeSettings& settings);

// A 64-bit hash (hex) of everything the volume depends on: positions, indices, uvs, material
// albedos, metallic and specular, textures, the voxel settings and the voxelizer's revision.
std::string geometryHash(const Scene& scene, const VoxelizeSettings& settings);

// .vdb files: all grids of all levels plus file metadata. Written to a temporary file then
// renamed. Reading throws InputError ("<path>: <problem>") on absent, corrupt or foreign files.
void writeGeometryVolume(const std::string& path, const SparseGeometryVolume& volume);
SparseGeometryVolume readGeometryVolume(const std::string& path);

// Reuses cacheDir/geometry-<hash>.vdb when it exists and its hash matches, else voxelizes and
// writes it. `fromCache` (optional) tells which happened.
SparseGeometryVolume loadOrBuildGeometryVolume(const Scene& scene, const VoxelizeSettings& settings,
                                         const std::string& cacheDir, bool* fromCache = nullptr);

// Grid names: level 0 has the plain name ("occupancy"), level L > 0 the suffix "_L<L>".
std::string gridName(const std::string& base, int level);

}  // namespace voxgi
