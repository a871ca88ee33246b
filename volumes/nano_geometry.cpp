#include "volumes/nano_geometry.h"

#include <algorithm>
#include <cstring>
#include <string>

#include <nanovdb/NanoVDB.h>
#include <nanovdb/util/OpenToNanoVDB.h>
#include <openvdb/tools/Prune.h>
#include <tbb/parallel_for.h>

#include "scenes/errors.h"
#include "scenes/memory_limit.h"
#include "volumes/blocker_sh.h"
#include "volumes/detail/geometry_grids.h"

namespace voxgi {

namespace {

// An OpenVDB grid on the occupancy's topology holding `value(index, ijk)` of every occupied
// voxel that `holdsSurface(index)` (index: the voxel's slot in the level's attribute arrays);
// the other voxels are dropped.
template <typename Grid, typename Keep, typename Value>
typename Grid::Ptr attributeGrid(const detail::LevelGrids& level, const Keep& holdsSurface, const Value& value) {
    using Tree = typename Grid::TreeType;
    auto tree = std::make_shared<Tree>(level.occupancy->tree(), typename Grid::ValueType(0.0f), openvdb::TopologyCopy());
    std::vector<typename Tree::LeafNodeType*> leaves;
    tree->getNodes(leaves);
    tbb::parallel_for(std::size_t(0), leaves.size(), [&](std::size_t i) {
        for (auto it = leaves[i]->beginValueOn(); it; ++it) {
            const std::int64_t slot = level.attributeIndex(it.getCoord());
            if (slot >= 0 && holdsSurface(std::size_t(slot))) it.setValue(value(std::size_t(slot), it.getCoord()));
            else it.setValueOff();
        }
    });
    openvdb::tools::pruneInactive(*tree);
    return Grid::create(tree);
}

template <typename Grid>
void append(NanoGeometry& out, const Grid& grid, std::uint32_t& offset) {
    auto handle = nanovdb::openToNanoVDB(grid, nanovdb::StatsMode::BBox, nanovdb::ChecksumMode::Disable);
    const std::uint64_t start = out.bytes(), size = handle.size();
    if (start + size > (std::uint64_t(1) << 32) - 1)
        throw InputError("geometry volume: " + std::to_string((start + size) >> 20) +
                         " MiB of NanoVDB grids pass the GPU's 32-bit addresses");
    offset = std::uint32_t(start);
    out.words.resize(std::size_t((start + size + 31) / 32 * 8), 0u);  // keep the next grid 32-byte aligned
    std::memcpy(reinterpret_cast<unsigned char*>(out.words.data()) + start, handle.data(), std::size_t(size));
}

// NanoVDB bytes of a grid of `Value` on the occupancy's topology (its nodes; the grid, tree
// and root headers and the root's tiles within 64 KiB).
template <typename Value>
double nanoGridBytes(const std::vector<openvdb::Index32>& nodes) {
    using Tree = typename nanovdb::NanoTree<Value>;
    return double(nodes[0]) * double(sizeof(typename Tree::LeafNodeType)) +
           double(nodes[1]) * double(sizeof(typename Tree::Node1)) +
           double(nodes[2]) * double(sizeof(typename Tree::Node2)) + 65536.0;
}

}  // namespace

double nanoGeometryBytes(const SparseGeometryVolume& volume, int level, bool surfaceOffsets) {
    const detail::LevelGrids& l = volume.grids().levels.at(std::size_t(level));
    const std::vector<openvdb::Index32> nodes = l.occupancy->tree().nodeCount();
    const double vec3 = nanoGridBytes<nanovdb::Vec3f>(nodes);
    const double buffer = 2.0 * vec3 + (surfaceOffsets ? nanoGridBytes<float>(nodes) : 0.0);
    // While a grid is converted, its OpenVDB copy (leaves of 512 values) and its NanoVDB handle
    // live beside the buffer.
    const double openVdbVec3 = double(nodes[0]) * 512.0 * double(sizeof(openvdb::Vec3f)) * 1.1;
    const double surfaces = surfaceOffsets ? double(l.normalC0.size()) * double(sizeof(VoxelSurface)) : 0.0;
    return buffer + vec3 + openVdbVec3 + surfaces;
}

NanoGeometry makeNanoGeometry(const SparseGeometryVolume& volume, int level, const SurfaceProbe& surfaceProbe) {
    const detail::LevelGrids& l = volume.grids().levels.at(std::size_t(level));
    requireMemory(nanoGeometryBytes(volume, level, bool(surfaceProbe)),
                  "the NanoVDB geometry volume (" + std::to_string(l.occupancy->activeVoxelCount()) + " voxels)");
    NanoGeometry out;
    out.voxelSize = float(l.voxelSize);
    const BlockerFit fit = volume.grids().blockerFit;
    // Voxels a surface only touches (it lies on their face and its area went to the neighbour)
    // hold no surface and are dropped: traced as solid, they were hit with no normal beside the
    // real surface's voxel (the layer under the Cornell box's ceiling, lit by the light just
    // below it).
    auto holdsSurface = [&](std::size_t i) {
        return coverageFromBlocker(l.normalC0[i].w, glm::vec3(l.normalC0[i]), fit) > 0.0f;
    };
    // Unit mean normal times consistency (|sum a n| / sum a), per attribute slot.
    auto meanNormal = [&](std::size_t i) {
        const glm::vec3 m(l.normalC0[i]);
        const float length = glm::length(m), area = coverageFromBlocker(l.normalC0[i].w, m, fit);
        if (!(length > 0.0f) || !(area > 0.0f)) return glm::vec3(0.0f);
        return m * (std::min(1.0f, length / area) / length);
    };
    // One grid at a time, each converted before the next is built (nanoGeometryBytes' peak).
    {
        const auto normal = attributeGrid<openvdb::Vec3fGrid>(l, holdsSurface, [&](std::size_t i, const openvdb::Coord&) {
            const glm::vec3 n = meanNormal(i);
            return openvdb::Vec3f(n.x, n.y, n.z);
        });
        out.activeVoxels = normal->activeVoxelCount();
        append(out, *normal, out.normalGrid);
    }
    // The probe's answers per slot (each written once, from one thread).
    std::vector<VoxelSurface> surfaces(surfaceProbe ? l.normalC0.size() : 0);
    if (surfaceProbe) {
        const auto offset = attributeGrid<openvdb::FloatGrid>(l, holdsSurface, [&](std::size_t i, const openvdb::Coord& c) {
            const glm::vec3 n = meanNormal(i);
            if (n == glm::vec3(0.0f)) return 0.0f;
            const glm::vec3 centre = (glm::vec3(float(c.x()), float(c.y()), float(c.z())) + 0.5f) * out.voxelSize;
            surfaces[i] = surfaceProbe(centre, glm::normalize(n));
            return surfaces[i].offset;
        });
        append(out, *offset, out.offsetGrid);
    }
    const auto albedo = attributeGrid<openvdb::Vec3fGrid>(l, holdsSurface, [&](std::size_t i, const openvdb::Coord&) {
        const glm::vec3 a = !surfaces.empty() && surfaces[i].albedoSeen ? surfaces[i].albedo
                                                                         : detail::fromHalves(l.albedo[i]);
        return openvdb::Vec3f(a.x, a.y, a.z);
    });
    append(out, *albedo, out.albedoGrid);
    return out;
}

}  // namespace voxgi
