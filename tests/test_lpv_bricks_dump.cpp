// The ordinates' light volumes dumped brick by brick (gi/lpv/lpv_dump.h): each stored brick one
// OpenVDB leaf, every voxel where the transport has light, at its cell's world position.
#include <gtest/gtest.h>
#include <openvdb/openvdb.h>

#include "gi/lpv/lpv_dump.h"
#include "support/test_support.h"
#include "volumes/openvdb_setup.h"

using namespace voxgi;

TEST(LpvBricksDump, EachBrickIsALeafAtItsCellsWorldPosition) {
    CascadeGrid g;
    g.origin = {-13, 5, 3};  // not a multiple of 8: bricks start at the grid's first cell
    g.resolution = 24;
    g.cellSize = 0.25f;
    OrdinatesTransport t(g, 2);
    std::vector<OrdinateSurface> floor;
    for (int z = 2; z < 10; ++z)
        for (int x = 2; x < 10; ++x) floor.push_back({{x, 1, z}, 1.0f, {0.0f, 1.0f, 0.0f}, glm::vec3(0.5f)});
    t.addSurfaces(floor);
    OrdinatesTransport::Sources s = t.emptySources();
    SurfelSource lit;
    for (int z = 2; z < 10; ++z)
        for (int x = 2; x < 10; ++x) {
            Surfel f;
            f.position = g.cellCenter({x, 1, z});
            f.normal = {0.0f, 1.0f, 0.0f};
            f.flux = glm::vec3(1.0f, 0.5f, 0.25f);
            lit.surfels.push_back(f);
        }
    t.addSurfels(lit, 0.0f, s);
    const IrradianceBricks e = t.solve(s, true, 4);
    ASSERT_LT(t.bricks().slots(), 27u) << "every brick stored";

    const std::string path = test::makeTempDir("lpv-bricks-dump") + "/o.vdb";
    writeOrdinatesVdb(path, {{&t, e}});
    initializeOpenVdb();
    openvdb::io::File file(path);
    file.open();
    auto grid = openvdb::gridPtrCast<openvdb::Vec3SGrid>(file.readGrid("irradiance_ny_L0"));
    file.close();
    ASSERT_TRUE(grid);
    EXPECT_LE(grid->tree().leafCount(), t.bricks().slots());
    EXPECT_GT(grid->tree().leafCount(), 0u);
    std::size_t voxels = 0;
    for (auto v = grid->cbeginValueOn(); v; ++v) {
        ASSERT_TRUE(v.isVoxelValue()) << "a tile where a leaf was written";
        const openvdb::Coord c = v.getCoord();
        const glm::ivec3 cell(c.x(), c.y(), c.z());
        // Index space from the grid's first cell; world positions at the cell centres.
        const openvdb::Vec3d w = grid->indexToWorld(c);
        const glm::vec3 centre = g.cellCenter(cell);
        EXPECT_NEAR(w.x(), centre.x, 1e-5);
        EXPECT_NEAR(w.y(), centre.y, 1e-5);
        EXPECT_NEAR(w.z(), centre.z, 1e-5);
        const glm::vec4 expected = t.irradianceAt(e, cell, 3);
        EXPECT_EQ(v->x(), expected.x);
        EXPECT_EQ(v->z(), expected.z);
        ++voxels;
    }
    // Every stored cell with light is a voxel.
    std::size_t lit3 = 0;
    for (int z = 0; z < g.resolution; ++z)
        for (int y = 0; y < g.resolution; ++y)
            for (int x = 0; x < g.resolution; ++x) {
                const glm::vec4 v = t.irradianceAt(e, {x, y, z}, 3);
                if (v.x != 0.0f || v.y != 0.0f || v.z != 0.0f) ++lit3;
            }
    EXPECT_EQ(voxels, lit3);
    EXPECT_GT(voxels, 0u);
}
