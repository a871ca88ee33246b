// Compact levels -> the dense, annotated OpenVDB grids a .vdb file holds (the layout every
// OpenVDB tool reads: one grid per attribute, the occupancy's active voxels in each).
#include <tbb/parallel_for.h>

#include "volumes/detail/geometry_grids.h"

namespace voxgi::detail {

namespace {

void annotate(openvdb::GridBase& grid, const std::string& name, const char* role, int level, double voxelSize,
              const GeometryGrids& g) {
    grid.setName(name);
    grid.insertMeta("voxgi_class", openvdb::StringMetadata(role));
    grid.insertMeta("voxgi_level", openvdb::Int32Metadata(level));
    grid.insertMeta("voxgi_voxel_size", openvdb::DoubleMetadata(voxelSize));
    grid.insertMeta("voxgi_source_hash", openvdb::StringMetadata(g.sourceHash));
    grid.insertMeta("voxgi_version", openvdb::StringMetadata(VOXGI_VERSION));
}

// One dense grid with the occupancy's topology; `value(index)` gives an active voxel's value
// from its attribute index.
template <typename GridT, typename ValueFn>
typename GridT::Ptr expandAttribute(const LevelGrids& l, const std::vector<const OccupancyLeaf*>& leaves,
                                    const ValueFn& value) {
    using LeafT = typename GridT::TreeType::LeafNodeType;
    const typename GridT::ValueType zero = openvdb::zeroVal<typename GridT::ValueType>();
    std::vector<LeafT*> built(leaves.size());
    tbb::parallel_for(std::size_t(0), leaves.size(), [&](std::size_t i) {
        auto* leaf = new LeafT(leaves[i]->origin(), zero);
        std::size_t index = leaves[i]->transientData();
        for (auto it = leaves[i]->cbeginValueOn(); it; ++it, ++index) leaf->setValueOn(it.pos(), value(index));
        built[i] = leaf;
    });
    typename GridT::Ptr grid = GridT::create(zero);
    for (LeafT* leaf : built) grid->tree().addLeaf(leaf);
    grid->setTransform(l.occupancy->transform().copy());
    return grid;
}

void appendLevel(const GeometryGrids& g, int level, openvdb::GridPtrVec& out) {
    const LevelGrids& l = g.levels[std::size_t(level)];
    std::vector<const OccupancyLeaf*> leaves;
    leaves.reserve(l.occupancy->tree().leafCount());
    for (auto it = l.occupancy->constTree().cbeginLeaf(); it; ++it) leaves.push_back(it.getLeaf());

    // A shallow copy: the file's occupancy grid shares the in-memory tree, with its own metadata.
    openvdb::BoolGrid::Ptr occupancy = l.occupancy->copy();
    annotate(*occupancy, gridName("occupancy", level), "occupancy", level, l.voxelSize, g);
    occupancy->setGridClass(openvdb::GRID_FOG_VOLUME);
    out.push_back(occupancy);

    auto albedo = expandAttribute<openvdb::Vec3fGrid>(l, leaves, [&](std::size_t i) {
        glm::vec3 a = fromHalves(l.albedo[i]);
        return openvdb::Vec3f(a.x, a.y, a.z);
    });
    annotate(*albedo, gridName("albedo", level), "albedo", level, l.voxelSize, g);
    albedo->setGridClass(openvdb::GRID_UNKNOWN);
    albedo->setVectorType(openvdb::VEC_INVARIANT);
    out.push_back(albedo);

    auto normal = expandAttribute<openvdb::Vec3fGrid>(l, leaves, [&](std::size_t i) {
        const glm::vec4& n = l.normalC0[i];
        return openvdb::Vec3f(n.x, n.y, n.z);
    });
    annotate(*normal, gridName("normal", level), "normal", level, l.voxelSize, g);
    normal->setGridClass(openvdb::GRID_UNKNOWN);
    normal->setVectorType(openvdb::VEC_COVARIANT);
    out.push_back(normal);

    for (int c = 0; c < 4; ++c) {
        auto b = expandAttribute<openvdb::FloatGrid>(l, leaves, [&](std::size_t i) {
            const glm::vec4& n = l.normalC0[i];
            return blockerSH(n.w, glm::vec3(n), g.blockerFit)[c];
        });
        annotate(*b, gridName("blocker_sh" + std::to_string(c), level), "blocker", level, l.voxelSize, g);
        b->setGridClass(openvdb::GRID_UNKNOWN);
        b->insertMeta("voxgi_sh_index", openvdb::Int32Metadata(c));
        b->insertMeta("voxgi_sh_convention",
                      openvdb::StringMetadata("B(w)=clamp(sum c_i Y_i(w),0,1); (c0,c1,c2,c3)=(Y00,Y1-1,Y10,Y11); "
                                              "Y00=0.282094792, Y1-1=-0.488602512*y, Y10=0.488602512*z, "
                                              "Y11=-0.488602512*x"));
        b->insertMeta("voxgi_blocker_fit", openvdb::StringMetadata(blockerFitName(g.blockerFit)));
        out.push_back(b);
    }
    auto projected = expandAttribute<openvdb::Vec3fGrid>(l, leaves, [&](std::size_t i) {
        const glm::vec3 p = fromHalves(l.projected[i]);
        return openvdb::Vec3f(p.x, p.y, p.z);
    });
    annotate(*projected, gridName("projected_coverage", level), "projected_coverage", level, l.voxelSize, g);
    projected->setGridClass(openvdb::GRID_UNKNOWN);
    projected->setVectorType(openvdb::VEC_INVARIANT);
    projected->insertMeta("voxgi_meaning", openvdb::StringMetadata(
        "per axis a: sum of clipped triangle area * |normal_a| / voxel face area"));
    out.push_back(projected);
}

}  // namespace

openvdb::GridPtrVec expandGrids(const GeometryGrids& g) {
    openvdb::GridPtrVec grids;
    for (std::size_t level = 0; level < g.levels.size(); ++level) appendLevel(g, int(level), grids);
    if (g.sdf) {
        openvdb::FloatGrid::Ptr sdf = g.sdf->copy();
        annotate(*sdf, "sdf", "sdf", 0, g.levels.empty() ? 0.0 : g.levels[0].voxelSize, g);
        sdf->setGridClass(openvdb::GRID_LEVEL_SET);
        grids.push_back(sdf);
    }
    return grids;
}

}  // namespace voxgi::detail
