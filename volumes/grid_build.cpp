// Voxel sums -> coarser levels and finished OpenVDB grids. Leaves are finalized in parallel,
// then linked into the trees serially (addLeaf is cheap next to filling 512 voxels).
#include <map>
#include <tuple>

#include <tbb/parallel_for.h>

#include "volumes/detail/accumulation.h"
#include "volumes/detail/grid_build.h"

namespace voxgi::detail {

AccumLeaf::AccumLeaf(const glm::ivec3& origin) : origin_(origin) {
    openvdb::Coord o(origin.x, origin.y, origin.z);
    occupancy_ = std::make_unique<openvdb::BoolTree::LeafNodeType>(o, false);
    albedo_ = std::make_unique<openvdb::Vec3fTree::LeafNodeType>(o, openvdb::Vec3f(0.0f));
    normal_ = std::make_unique<openvdb::Vec3fTree::LeafNodeType>(o, openvdb::Vec3f(0.0f));
    for (auto& b : blocker_) b = std::make_unique<openvdb::FloatTree::LeafNodeType>(o, 0.0f);
}

void AccumLeaf::translate(const glm::ivec3& delta) {
    origin_ += delta;
    openvdb::Coord o(origin_.x, origin_.y, origin_.z);
    occupancy_->setOrigin(o);
    albedo_->setOrigin(o);
    normal_->setOrigin(o);
    for (auto& b : blocker_) b->setOrigin(o);
}

void AccumLeaf::add(int offset, const VoxelSums& s) {
    const auto i = openvdb::Index(offset);
    occupancy_->setValueOn(i, true);
    blocker_[0]->buffer().data()[i] += s.area;
    blocker_[1]->buffer().data()[i] += s.albedoWeight;
    normal_->buffer().data()[i] += openvdb::Vec3f(s.vectorArea.x, s.vectorArea.y, s.vectorArea.z);
    albedo_->buffer().data()[i] += openvdb::Vec3f(s.albedoSum.x, s.albedoSum.y, s.albedoSum.z);
}

VoxelSums AccumLeaf::sums(int offset) const {
    const auto i = openvdb::Index(offset);
    VoxelSums s;
    s.area = blocker_[0]->getValue(i);
    s.albedoWeight = blocker_[1]->getValue(i);
    const openvdb::Vec3f& n = normal_->getValue(i);
    const openvdb::Vec3f& a = albedo_->getValue(i);
    s.vectorArea = {n.x(), n.y(), n.z()};
    s.albedoSum = {a.x(), a.y(), a.z()};
    return s;
}

void AccumLeaf::finalizeValues(BlockerFit fit) {
    for (auto it = occupancy_->cbeginValueOn(); it; ++it) {
        const openvdb::Index i = it.pos();
        VoxelSums s = sums(int(i));
        glm::vec3 albedo = s.albedoWeight > 0.0f ? s.albedoSum / s.albedoWeight : glm::vec3(0.0f);
        glm::vec4 sh = blockerFromCoverage(s.area, s.vectorArea, fit);
        albedo_->setValueOnly(i, openvdb::Vec3f(albedo.x, albedo.y, albedo.z));
        for (int c = 0; c < 4; ++c) blocker_[c]->setValueOnly(i, sh[c]);
    }
    // Every grid of a level has the occupancy's active voxels.
    albedo_->setValueMask(occupancy_->getValueMask());
    normal_->setValueMask(occupancy_->getValueMask());
    for (auto& b : blocker_) b->setValueMask(occupancy_->getValueMask());
}

void AccumLeaf::moveInto(LevelGrids& g) {
    g.occupancy->tree().addLeaf(occupancy_.release());
    g.albedo->tree().addLeaf(albedo_.release());
    g.normal->tree().addLeaf(normal_.release());
    for (int c = 0; c < 4; ++c) g.blocker[c]->tree().addLeaf(blocker_[c].release());
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
    tbb::parallel_for(std::size_t(0), work.size(), [&](std::size_t i) {
        auto leaf = std::make_unique<AccumLeaf>(work[i].first);
        for (const AccumLeaf* child : work[i].second) {
            for (int o = 0; o < 512; ++o) {
                if (!child->on(o)) continue;
                glm::ivec3 p = (child->origin() + glm::ivec3(o >> 6, (o >> 3) & 7, o & 7)) >> 1;
                VoxelSums s = child->sums(o);
                // Areas are in face units of their level; a coarse face is 4 fine faces.
                s.area *= 0.25f;
                s.vectorArea *= 0.25f;
                s.albedoSum *= 0.25f;
                s.albedoWeight *= 0.25f;
                leaf->add(AccumLeaf::offset(p.x, p.y, p.z), s);
            }
        }
        coarse[i] = std::move(leaf);
    });
    return coarse;
}

LevelGrids buildLevelGrids(AccumLevel&& level, double voxelSize, BlockerFit fit) {
    tbb::parallel_for(std::size_t(0), level.size(), [&](std::size_t i) { level[i]->finalizeValues(fit); });
    LevelGrids g;
    g.voxelSize = voxelSize;
    auto xform = voxelTransform(voxelSize);
    g.occupancy = openvdb::BoolGrid::create(false);
    g.albedo = openvdb::Vec3fGrid::create(openvdb::Vec3f(0.0f));
    g.normal = openvdb::Vec3fGrid::create(openvdb::Vec3f(0.0f));
    for (auto& b : g.blocker) b = openvdb::FloatGrid::create(0.0f);
    for (auto& leaf : level) leaf->moveInto(g);
    level.clear();
    g.occupancy->setTransform(xform);
    g.albedo->setTransform(xform->copy());
    g.normal->setTransform(xform->copy());
    for (auto& b : g.blocker) b->setTransform(xform->copy());
    return g;
}

}  // namespace voxgi::detail
