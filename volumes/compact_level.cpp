// The compact in-memory level: attribute lookup through the occupancy topology, albedo and
// projected-coverage quantization, and turning a file's dense grids back into the compact form.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <mutex>
#include <optional>

#include <tbb/parallel_for.h>

#include "scenes/errors.h"
#include "volumes/detail/geometry_grids.h"

namespace voxgi::detail {

namespace {

// Active voxels of the leaf mask at offsets below n.
std::uint32_t activeBelow(const OccupancyLeaf::NodeMaskType& mask, openvdb::Index n) {
    const openvdb::Index word = n >> 6;
    std::uint32_t count = 0;
    for (openvdb::Index w = 0; w < word; ++w) count += std::uint32_t(__builtin_popcountll(mask.getWord<openvdb::Index64>(w)));
    const openvdb::Index64 below = (openvdb::Index64(1) << (n & 63)) - 1;
    return count + std::uint32_t(__builtin_popcountll(mask.getWord<openvdb::Index64>(word) & below));
}

std::vector<OccupancyLeaf*> leavesOf(openvdb::BoolTree& tree) {
    std::vector<OccupancyLeaf*> leaves;
    leaves.reserve(tree.leafCount());
    for (auto it = tree.beginLeaf(); it; ++it) leaves.push_back(it.getLeaf());
    return leaves;
}

}  // namespace

std::int64_t LevelGrids::attributeIndex(const openvdb::Coord& ijk) const {
    const OccupancyLeaf* leaf = occupancy->constTree().probeConstLeaf(ijk);
    if (!leaf) return -1;
    const openvdb::Index n = OccupancyLeaf::coordToOffset(ijk);
    const auto& mask = leaf->getValueMask();
    if (!mask.isOn(n)) return -1;
    return std::int64_t(leaf->transientData()) + activeBelow(mask, n);
}

std::uint64_t LevelGrids::memoryBytes() const {
    return occupancy->memUsage() + normalC0.capacity() * sizeof(glm::vec4) + (albedo.capacity() + projected.capacity()) * sizeof(Half3);
}

Half3 toHalves(const glm::vec3& value) {
    Half3 h;
    for (int c = 0; c < 3; ++c) h[std::size_t(c)] = openvdb::math::half(std::clamp(value[c], -65504.0f, 65504.0f));
    return h;
}

glm::vec3 fromHalves(const Half3& value) {
    return glm::vec3(float(value[0]), float(value[1]), float(value[2]));
}

std::uint64_t indexLeaves(openvdb::BoolTree& tree) {
    std::uint64_t count = 0;
    for (auto it = tree.beginLeaf(); it; ++it) {
        if (count > std::numeric_limits<openvdb::Index32>::max())
            throw InputError("--voxel-size: more than 2^32 occupied voxels in one level; use a larger voxel size");
        it->setTransientData(openvdb::Index32(count));
        count += it->onVoxelCount();
    }
    return count;
}

LevelGrids compactLevel(LevelFileGrids&& file, BlockerFit fit, const std::string& path) {
    LevelGrids level;
    level.voxelSize = file.occupancy->voxelSize()[0];
    level.occupancy = std::move(file.occupancy);
    openvdb::BoolTree& tree = level.occupancy->tree();
    tree.voxelizeActiveTiles();
    const std::uint64_t active = indexLeaves(tree);
    level.normalC0.resize(active);
    level.albedo.resize(active);
    level.projected.resize(active);
    const std::vector<OccupancyLeaf*> leaves = leavesOf(tree);

    std::mutex mismatchMutex;
    std::string mismatch;  // the first bad value found, named by grid and voxel
    auto refuse = [&](const openvdb::GridBase& grid, const openvdb::Coord& ijk, const std::string& what) {
        std::lock_guard<std::mutex> lock(mismatchMutex);
        if (mismatch.empty())
            mismatch = "grid '" + grid.getName() + "' at voxel (" + std::to_string(ijk.x()) + ", " + std::to_string(ijk.y()) +
                       ", " + std::to_string(ijk.z()) + ") " + what;
    };
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, leaves.size()), [&](const tbb::blocked_range<std::size_t>& r) {
        auto albedo = file.albedo->getConstAccessor();
        auto normal = file.normal->getConstAccessor();
        std::optional<openvdb::Vec3fGrid::ConstAccessor> projected;
        if (file.projected) projected.emplace(file.projected->getConstAccessor());
        std::array<openvdb::FloatGrid::ConstAccessor, 4> blocker = {
            file.blocker[0]->getConstAccessor(), file.blocker[1]->getConstAccessor(),
            file.blocker[2]->getConstAccessor(), file.blocker[3]->getConstAccessor()};
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
            std::size_t index = leaves[i]->transientData();
            for (auto it = leaves[i]->cbeginValueOn(); it; ++it, ++index) {
                const openvdb::Coord ijk = it.getCoord();
                const openvdb::Vec3f a = albedo.getValue(ijk), n = normal.getValue(ijk);
                const glm::vec3 m(n.x(), n.y(), n.z());
                const glm::vec4 stored(blocker[0].getValue(ijk), blocker[1].getValue(ijk), blocker[2].getValue(ijk),
                                       blocker[3].getValue(ijk));
                // c1..c3 are rebuilt from the normal; a file whose blocker says otherwise would
                // silently change meaning, so it is refused (float rounding of rewriters allowed).
                const glm::vec4 derived = blockerSH(stored[0], m, fit);
                for (int c = 1; c < 4; ++c) {
                    if (std::abs(derived[c] - stored[c]) <= 1e-5f * (1.0f + std::abs(stored[c]))) continue;
                    refuse(*file.blocker[std::size_t(c)], ijk,
                           "is " + std::to_string(stored[c]) + ", not the " + std::to_string(derived[c]) +
                               " its normal grid implies");
                }
                level.normalC0[index] = glm::vec4(m, stored[0]);
                level.albedo[index] = toHalves(glm::vec3(a.x(), a.y(), a.z()));
                glm::vec3 p;
                if (projected) {
                    const openvdb::Vec3f v = projected->getValue(ijk);
                    p = glm::vec3(v.x(), v.y(), v.z());
                    // Areas: a negative or non-finite one would make light out of nothing.
                    if (!(p.x >= 0.0f && p.y >= 0.0f && p.z >= 0.0f && p.x + p.y + p.z < 3e38f)) {
                        refuse(*file.projected, ijk, "is not a finite, non-negative area");
                        p = glm::vec3(0.0f);
                    }
                } else {
                    p = isotropicProjectedCoverage(coverageFromBlocker(stored[0], m, fit), m);
                }
                level.projected[index] = toHalves(p);
            }
        }
    });
    if (!mismatch.empty()) throw InputError(path + ": " + mismatch);
    return level;
}

}  // namespace voxgi::detail
