#include "volumes/nano_geometry.h"

#include <algorithm>
#include <cstring>
#include <string>

#include <nanovdb/NanoVDB.h>
#include <nanovdb/util/OpenToNanoVDB.h>
#include <tbb/parallel_for.h>

#include "scenes/errors.h"
#include "scenes/memory_limit.h"
#include "volumes/blocker_sh.h"
#include "volumes/detail/geometry_grids.h"

namespace voxgi {

namespace {

// An OpenVDB grid on the occupancy's topology holding `value(index, ijk)` of every occupied
// voxel (index: the voxel's slot in the level's attribute arrays).
template <typename Grid, typename Value>
typename Grid::Ptr attributeGrid(const detail::LevelGrids& level, const Value& value) {
    using Tree = typename Grid::TreeType;
    auto tree = std::make_shared<Tree>(level.occupancy->tree(), typename Grid::ValueType(0.0f), openvdb::TopologyCopy());
    std::vector<typename Tree::LeafNodeType*> leaves;
    tree->getNodes(leaves);
    tbb::parallel_for(std::size_t(0), leaves.size(), [&](std::size_t i) {
        for (auto it = leaves[i]->beginValueOn(); it; ++it) {
            const std::int64_t slot = level.attributeIndex(it.getCoord());
            if (slot >= 0) it.setValue(value(std::size_t(slot), it.getCoord()));
        }
    });
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
    return buffer + vec3 + openVdbVec3;
}

NanoGeometry makeNanoGeometry(const SparseGeometryVolume& volume, int level, const SurfaceOffset& surfaceOffset) {
    const detail::LevelGrids& l = volume.grids().levels.at(std::size_t(level));
    requireMemory(nanoGeometryBytes(volume, level, bool(surfaceOffset)),
                  "the NanoVDB geometry volume (" + std::to_string(l.occupancy->activeVoxelCount()) + " voxels)");
    NanoGeometry out;
    out.voxelSize = float(l.voxelSize);
    out.activeVoxels = l.occupancy->activeVoxelCount();
    const BlockerFit fit = volume.grids().blockerFit;
    const auto normal = attributeGrid<openvdb::Vec3fGrid>(l, [&](std::size_t i, const openvdb::Coord&) {
        const glm::vec3 m(l.normalC0[i]);
        const float length = glm::length(m), area = coverageFromBlocker(l.normalC0[i].w, m, fit);
        if (!(length > 0.0f) || !(area > 0.0f)) return openvdb::Vec3f(0.0f);
        const glm::vec3 n = m * (std::min(1.0f, length / area) / length);
        return openvdb::Vec3f(n.x, n.y, n.z);
    });
    const auto albedo = attributeGrid<openvdb::Vec3fGrid>(l, [&](std::size_t i, const openvdb::Coord&) {
        const glm::vec3 a = detail::dequantizeAlbedo(l.albedo[i]);
        return openvdb::Vec3f(a.x, a.y, a.z);
    });
    append(out, *normal, out.normalGrid);
    append(out, *albedo, out.albedoGrid);
    if (surfaceOffset) {
        const auto offset = attributeGrid<openvdb::FloatGrid>(l, [&](std::size_t i, const openvdb::Coord& c) {
            const glm::vec3 n(l.normalC0[i]);
            const float length = glm::length(n);
            if (!(length > 0.0f)) return 0.0f;
            const glm::vec3 centre = (glm::vec3(float(c.x()), float(c.y()), float(c.z())) + 0.5f) * out.voxelSize;
            return surfaceOffset(centre, n / length);
        });
        append(out, *offset, out.offsetGrid);
    }
    return out;
}

}  // namespace voxgi
