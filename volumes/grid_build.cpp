// Voxel sums -> coarser levels and OpenVDB grids. Leaves are filled in parallel, then linked
// into the trees serially (addLeaf is cheap next to filling 512 voxels).
#include <map>
#include <tuple>

#include <tbb/parallel_for.h>

#include "volumes/detail/accumulation.h"
#include "volumes/detail/grid_build.h"

namespace voxgi::detail {

AccumLevel downsample(const AccumLevel& fine) {
    // Parents by leaf origin; each gathers its (up to 8) children.
    std::map<std::tuple<int, int, int>, std::vector<const AccumLeaf*>> parents;
    for (const auto& leaf : fine) {
        glm::ivec3 p = (leaf->origin >> 1) & ~7;
        parents[{p.x, p.y, p.z}].push_back(leaf.get());
    }
    std::vector<std::pair<glm::ivec3, std::vector<const AccumLeaf*>>> work;
    work.reserve(parents.size());
    for (auto& [key, children] : parents)
        work.push_back({glm::ivec3(std::get<0>(key), std::get<1>(key), std::get<2>(key)), std::move(children)});
    AccumLevel coarse(work.size());
    tbb::parallel_for(std::size_t(0), work.size(), [&](std::size_t i) {
        auto leaf = std::make_unique<AccumLeaf>();
        leaf->origin = work[i].first;
        for (const AccumLeaf* child : work[i].second) {
            for (int o = 0; o < 512; ++o) {
                if (!child->on(o)) continue;
                glm::ivec3 c = child->origin + glm::ivec3(o >> 6, (o >> 3) & 7, o & 7);
                glm::ivec3 p = c >> 1;
                int po = AccumLeaf::offset(p.x, p.y, p.z);
                leaf->touch(po);
                const VoxelSums& s = child->voxels[o];
                VoxelSums& d = leaf->voxels[po];
                // Areas are in face units of their level; a coarse face is 4 fine faces.
                d.area += 0.25f * s.area;
                d.vectorArea += 0.25f * s.vectorArea;
                d.albedoSum += 0.25f * s.albedoSum;
                d.albedoWeight += 0.25f * s.albedoWeight;
            }
        }
        coarse[i] = std::move(leaf);
    });
    return coarse;
}

LevelGrids buildLevelGrids(const AccumLevel& level, double voxelSize, BlockerFit fit) {
    using openvdb::Coord;
    const std::size_t n = level.size();
    std::vector<openvdb::BoolTree::LeafNodeType*> occ(n);
    std::vector<openvdb::Vec3fTree::LeafNodeType*> alb(n), nor(n);
    std::vector<std::array<openvdb::FloatTree::LeafNodeType*, 4>> blk(n);
    tbb::parallel_for(std::size_t(0), n, [&](std::size_t i) {
        const AccumLeaf& a = *level[i];
        Coord origin(a.origin.x, a.origin.y, a.origin.z);
        occ[i] = new openvdb::BoolTree::LeafNodeType(origin, false);
        alb[i] = new openvdb::Vec3fTree::LeafNodeType(origin, openvdb::Vec3f(0.0f));
        nor[i] = new openvdb::Vec3fTree::LeafNodeType(origin, openvdb::Vec3f(0.0f));
        for (auto& b : blk[i]) b = new openvdb::FloatTree::LeafNodeType(origin, 0.0f);
        for (openvdb::Index o = 0; o < 512; ++o) {
            if (!a.on(int(o))) continue;
            const VoxelSums& s = a.voxels[o];
            glm::vec3 albedo = s.albedoWeight > 0.0f ? s.albedoSum / s.albedoWeight : glm::vec3(0.0f);
            glm::vec4 sh = blockerFromCoverage(s.area, s.vectorArea, fit);
            occ[i]->setValueOn(o, true);
            alb[i]->setValueOn(o, openvdb::Vec3f(albedo.x, albedo.y, albedo.z));
            nor[i]->setValueOn(o, openvdb::Vec3f(s.vectorArea.x, s.vectorArea.y, s.vectorArea.z));
            for (int c = 0; c < 4; ++c) blk[i][c]->setValueOn(o, sh[c]);
        }
    });
    LevelGrids g;
    g.voxelSize = voxelSize;
    auto xform = voxelTransform(voxelSize);
    g.occupancy = openvdb::BoolGrid::create(false);
    g.albedo = openvdb::Vec3fGrid::create(openvdb::Vec3f(0.0f));
    g.normal = openvdb::Vec3fGrid::create(openvdb::Vec3f(0.0f));
    for (auto& b : g.blocker) b = openvdb::FloatGrid::create(0.0f);
    for (std::size_t i = 0; i < n; ++i) {
        g.occupancy->tree().addLeaf(occ[i]);
        g.albedo->tree().addLeaf(alb[i]);
        g.normal->tree().addLeaf(nor[i]);
        for (int c = 0; c < 4; ++c) g.blocker[c]->tree().addLeaf(blk[i][c]);
    }
    g.occupancy->setTransform(xform);
    g.albedo->setTransform(xform->copy());
    g.normal->setTransform(xform->copy());
    for (auto& b : g.blocker) b->setTransform(xform->copy());
    return g;
}

}  // namespace voxgi::detail
