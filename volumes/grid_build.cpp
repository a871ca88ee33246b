// Voxel sums -> coarser levels and finished compact levels. The occupancy leaves are linked into
// the tree serially (addLeaf is cheap), indexed in tree order, then every leaf writes its
// attributes in parallel, so a built level has the same layout as one read back from a file.
#include <map>
#include <tuple>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "volumes/detail/accumulation.h"
#include "volumes/detail/grid_build.h"

namespace voxgi::detail {

AccumLeaf::AccumLeaf(const glm::ivec3& origin)
    : origin_(origin), leaf_(new OccupancyLeaf(openvdb::Coord(origin.x, origin.y, origin.z), false)) {}

AccumLeaf::~AccumLeaf() {
    if (ownsLeaf_) delete leaf_;
}

void AccumLeaf::translate(const glm::ivec3& delta) {
    origin_ += delta;
    leaf_->setOrigin(openvdb::Coord(origin_.x, origin_.y, origin_.z));
}

void AccumLeaf::pack(DenseSums& dense) {
    packed_ = std::make_unique<VoxelSums[]>(leaf_->onVoxelCount());
    std::size_t i = 0;
    for (auto it = leaf_->cbeginValueOn(); it; ++it, ++i) {
        VoxelSums& v = dense.voxel[it.pos()];
        packed_[i] = v;
        v = VoxelSums{};
    }
}

void AccumLeaf::moveOccupancyInto(openvdb::BoolTree& tree) {
    tree.addLeaf(leaf_);
    ownsLeaf_ = false;
}

void AccumLeaf::writeAttributes(LevelGrids& level, BlockerFit fit) const {
    std::size_t index = leaf_->transientData();
    forEachActive([&](int, const VoxelSums& s) {
        glm::vec3 albedo = s.albedoWeight > 0.0f ? s.albedoSum / s.albedoWeight : glm::vec3(0.0f);
        level.normalC0[index] = glm::vec4(s.vectorArea, blockerFromCoverage(s.area, s.vectorArea, fit)[0]);
        level.albedo[index] = toHalves(albedo);
        level.projected[index] = toHalves(s.axisArea);
        ++index;
    });
}

AccumLevel downsample(const AccumLevel& fine) {
    // Parents by leaf origin; each gathers its (up to 8) children.
    std::map<std::tuple<int, int, int>, std::vector<const AccumLeaf*>> parents;
    for (const auto& leaf : fine) {
        glm::ivec3 p = (leaf->origin() >> 1) & ~7;
        parents[{p.x, p.y, p.z}].push_back(leaf.get());
    }
    std::vector<std::pair<glm::ivec3, std::vector<const AccumLeaf*>>> work;
    work.reserve(parents.size());
    for (auto& [key, children] : parents)
        work.push_back({glm::ivec3(std::get<0>(key), std::get<1>(key), std::get<2>(key)), std::move(children)});
    AccumLevel coarse(work.size());
    tbb::enumerable_thread_specific<std::unique_ptr<DenseSums>> scratch([] { return std::make_unique<DenseSums>(); });
    tbb::parallel_for(std::size_t(0), work.size(), [&](std::size_t i) {
        DenseSums& dense = *scratch.local();
        auto leaf = std::make_unique<AccumLeaf>(work[i].first);
        for (const AccumLeaf* child : work[i].second) {
            child->forEachActive([&](int o, VoxelSums s) {
                glm::ivec3 p = (child->origin() + glm::ivec3(o >> 6, (o >> 3) & 7, o & 7)) >> 1;
                // Areas are in face units of their level; a coarse face is 4 fine faces.
                s *= 0.25f;
                leaf->add(AccumLeaf::offset(p.x, p.y, p.z), s, dense);
            });
        }
        leaf->pack(dense);
        coarse[i] = std::move(leaf);
    });
    return coarse;
}

LevelGrids buildLevelGrids(AccumLevel&& level, double voxelSize, BlockerFit fit) {
    LevelGrids g;
    g.voxelSize = voxelSize;
    g.occupancy = openvdb::BoolGrid::create(false);
    g.occupancy->setTransform(voxelTransform(voxelSize));
    for (auto& leaf : level) leaf->moveOccupancyInto(g.occupancy->tree());
    const std::uint64_t active = indexLeaves(g.occupancy->tree());
    g.normalC0.resize(active);
    g.albedo.resize(active);
    g.projected.resize(active);
    tbb::parallel_for(std::size_t(0), level.size(), [&](std::size_t i) {
        level[i]->writeAttributes(g, fit);
        level[i].reset();
    });
    level.clear();
    return g;
}

}  // namespace voxgi::detail
