#include "gi/lpv/lpv_dump.h"

#include <memory>

#include <openvdb/openvdb.h>

#include "shaders/shared/light_bricks.h"
#include "volumes/openvdb_file.h"
#include "volumes/openvdb_setup.h"

namespace voxgi {

namespace {

openvdb::math::Transform::Ptr transformFor(float cellSize, bool cellCentred) {
    auto xform = openvdb::math::Transform::createLinearTransform(double(cellSize));
    // Light cells are centred at (i + 0.5) h; geometry samples sit on the corners i h.
    if (cellCentred) xform->postTranslate(openvdb::Vec3d(0.5 * double(cellSize)));
    return xform;
}

template <typename GridT>
void tag(GridT& grid, const std::string& name, int cascade, float cellSize) {
    grid.setName(name);
    grid.setGridClass(openvdb::GRID_FOG_VOLUME);
    grid.insertMeta("cascade", openvdb::Int32Metadata(cascade));
    grid.insertMeta("cell_size", openvdb::FloatMetadata(cellSize));
    grid.insertMeta("creator", openvdb::StringMetadata("voxgi " VOXGI_VERSION));
}

}  // namespace

void writeLpvVdb(const std::string& path, const std::vector<LightVolume>& light,
                 const std::vector<BlockerVolume>& geometry) {
    initializeOpenVdb();
    openvdb::GridPtrVec grids;
    for (std::size_t c = 0; c < light.size(); ++c) {
        const LightVolume& lv = light[c];
        const CascadeGrid& g = lv.grid;
        const char* names[3] = {"r", "g", "b"};
        const std::vector<glm::vec4>* data[3] = {&lv.r, &lv.g, &lv.b};
        for (int ch = 0; ch < 3; ++ch)
            for (int k = 0; k < 4; ++k) {
                auto grid = openvdb::FloatGrid::create(0.0f);
                grid->setTransform(transformFor(g.cellSize, true));
                tag(*grid, "lpv_" + std::string(names[ch]) + "_L" + std::to_string(c) + "_sh" + std::to_string(k),
                    int(c), g.cellSize);
                grid->insertMeta("sh_coefficient", openvdb::Int32Metadata(k));
                grid->insertMeta("units", openvdb::StringMetadata("W/sr"));
                auto acc = grid->getAccessor();
                for (int z = 0; z < g.resolution; ++z)
                    for (int y = 0; y < g.resolution; ++y)
                        for (int x = 0; x < g.resolution; ++x) {
                            float v = (*data[ch])[g.index({x, y, z})][k];
                            if (v != 0.0f) acc.setValue(openvdb::Coord(g.origin.x + x, g.origin.y + y, g.origin.z + z), v);
                        }
                grids.push_back(grid);
            }
        if (c >= geometry.size()) continue;
        const BlockerVolume& gv = geometry[c];
        const int n = gv.cornerCount();
        for (int k = 0; k < 4; ++k) {
            auto grid = openvdb::FloatGrid::create(0.0f);
            grid->setTransform(transformFor(g.cellSize, false));
            tag(*grid, "blocker_L" + std::to_string(c) + "_sh" + std::to_string(k), int(c), g.cellSize);
            grid->insertMeta("sh_coefficient", openvdb::Int32Metadata(k));
            auto acc = grid->getAccessor();
            for (int z = 0; z < n; ++z)
                for (int y = 0; y < n; ++y)
                    for (int x = 0; x < n; ++x) {
                        float v = gv.blocker[gv.cornerIndex({x, y, z})][k];
                        if (v != 0.0f) acc.setValue(openvdb::Coord(g.origin.x + x, g.origin.y + y, g.origin.z + z), v);
                    }
            grids.push_back(grid);
        }
        auto albedo = openvdb::Vec3SGrid::create(openvdb::Vec3s(0.0f));
        albedo->setTransform(transformFor(g.cellSize, false));
        tag(*albedo, "albedo_L" + std::to_string(c), int(c), g.cellSize);
        auto acc = albedo->getAccessor();
        for (int z = 0; z < n; ++z)
            for (int y = 0; y < n; ++y)
                for (int x = 0; x < n; ++x) {
                    glm::vec3 a = gv.albedo[gv.cornerIndex({x, y, z})];
                    if (a != glm::vec3(0.0f))
                        acc.setValue(openvdb::Coord(g.origin.x + x, g.origin.y + y, g.origin.z + z),
                                     openvdb::Vec3s(a.x, a.y, a.z));
                }
        grids.push_back(albedo);
    }
    writeVdbFile(path, grids);
}

void writeOrdinatesVdb(const std::string& path, const std::vector<OrdinatesDump>& cascades) {
    initializeOpenVdb();
    using Leaf = openvdb::Vec3SGrid::TreeType::LeafNodeType;
    static_assert(Leaf::DIM == shading::kBrickSide, "a brick is an OpenVDB leaf node");
    openvdb::GridPtrVec grids;
    const char* faces[kOrdinateFaces] = {"px", "nx", "py", "ny", "pz", "nz"};
    for (std::size_t c = 0; c < cascades.size(); ++c) {
        const OrdinatesTransport& t = *cascades[c].transport;
        const CascadeGrid& g = t.grid();
        const BrickMap& bricks = t.bricks();
        const IrradianceBricks& e = cascades[c].irradiance;
        for (int f = 0; f < kOrdinateFaces; ++f) {
            auto grid = openvdb::Vec3SGrid::create(openvdb::Vec3s(0.0f));
            // Index space from the cascade's first cell, so bricks are leaves (light_bricks.h).
            auto xform = transformFor(g.cellSize, true);
            xform->postTranslate(openvdb::Vec3d(g.origin.x, g.origin.y, g.origin.z) * double(g.cellSize));
            grid->setTransform(xform);
            tag(*grid, "irradiance_" + std::string(faces[f]) + "_L" + std::to_string(c), int(c), g.cellSize);
            grid->insertMeta("units", openvdb::StringMetadata("W/m^2"));
            if (e.size() < bricks.valueCount()) continue;
            for (std::size_t slot = 0; slot < bricks.slots(); ++slot) {
                const glm::ivec3 o = bricks.slotOrigins()[slot];
                const glm::vec4* values =
                    e.data() + shading::brickValue(int(bricks.slots()), shading::brickCell(int(slot), o), f);
                auto leaf = std::make_unique<Leaf>(openvdb::Coord(o.x, o.y, o.z), openvdb::Vec3s(0.0f), false);
                bool any = false;
                for (int i = 0; i < shading::kBrickCells; ++i) {
                    const glm::vec4 v = values[i];
                    // A brick's cells past the grid's edge hold nothing (no sweep reaches them).
                    if (v.x == 0.0f && v.y == 0.0f && v.z == 0.0f) continue;
                    // The brick runs x fastest, the leaf z fastest (light_bricks.h).
                    const openvdb::Coord at(i & 7, (i >> 3) & 7, i >> 6);
                    leaf->setValueOn(Leaf::coordToOffset(at), openvdb::Vec3s(v.x, v.y, v.z));
                    any = true;
                }
                if (any) grid->tree().addLeaf(leaf.release());
            }
            grids.push_back(grid);
        }
    }
    writeVdbFile(path, grids);
}

}  // namespace voxgi
