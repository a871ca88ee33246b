// Static blockers from the voxelized scene (gi/lpv/static_blockers.h): a surface's blocker sits
// on the corner plane behind it, so the light cell that holds the surface still receives the
// light arriving on its front (what the apply pass reads there), and the light stops at the
// surface's back. Before, each voxel's blocker went to all 8 corners, which also closed the
// cell's front face: a floor's cell got no light from above.
#include <gtest/gtest.h>

#include "gi/lpv/propagation.h"
#include "gi/lpv/static_blockers.h"
#include "volumes/blocker_sh.h"
#include "gi/sh/sh.h"
#include "shaders/shared/constants.h"
#include "volumes/geometry_volume.h"

using namespace voxgi;

namespace {

// A horizontal floor (facing +y, or -y when `down`) at height y0 spanning [-3, 3]^2 in x and z.
Scene floorScene(float y0, bool down) {
    Scene scene;
    Mesh mesh;
    mesh.name = "floor";
    mesh.positions = {{-3.0f, y0, -3.0f}, {-3.0f, y0, 3.0f}, {3.0f, y0, 3.0f}, {3.0f, y0, -3.0f}};
    mesh.indices = down ? std::vector<std::uint32_t>{0, 2, 1, 0, 3, 2} : std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3};
    mesh.materialIds = {0, 0};
    scene.meshes.push_back(mesh);
    Material white;
    white.albedo = glm::vec3(0.5f);
    scene.materials.push_back(white);
    return scene;
}

glm::vec4 toVec4(const sh::Sh4& s) { return {s.c[0], s.c[1], s.c[2], s.c[3]}; }

// Flux of the three colours' Y00 in a cell.
float flux(const LightVolume& v, glm::ivec3 c) { return v.r[v.grid.index(c)].x; }

}  // namespace

TEST(LpvStaticBlockers, AFloorBlocksBehindItselfAndItsCellTakesTheLightFromAbove) {
    for (bool down : {false, true}) {
        SCOPED_TRACE(down ? "facing down" : "facing up");
        // Voxels of 1 m: the floor at y = 0.3 lies inside voxel row j = 0, i.e. light cell row 0.
        VoxelizeSettings settings;
        settings.voxelSize = 1.0f;
        const SparseGeometryVolume voxels = voxelizeScene(floorScene(0.3f, down), settings);
        ASSERT_TRUE(voxels.occupied({0, 0, 0}));

        BlockerVolume geometry;
        CascadeGrid grid;
        grid.origin = glm::ivec3(-2, -2, -2);
        grid.resolution = 4;  // cells y = -2..1: the floor's cell is local row 2
        grid.cellSize = 1.0f;
        geometry.reset(grid);
        staticBlockers(voxels, 0, geometry);
        // Corner rows: world y = -2..2 is local 0..4; the floor's voxel spans world [0, 1], so its
        // back plane is world y = 0 (local 2) facing up, y = 1 (local 3) facing down.
        const int back = down ? 3 : 2, front = down ? 2 : 3;
        int blockedBack = 0, blockedFront = 0;
        for (int z = 0; z <= 4; ++z)
            for (int x = 0; x <= 4; ++x) {
                blockedBack += geometry.blocker[geometry.cornerIndex({x, back, z})] != glm::vec4(0.0f);
                blockedFront += geometry.blocker[geometry.cornerIndex({x, front, z})] != glm::vec4(0.0f);
            }
        EXPECT_EQ(blockedBack, 25);
        EXPECT_EQ(blockedFront, 0);

        // Light travelling toward the floor's front, one cell in front of it, for one step.
        const glm::vec3 towardFloor(0.0f, down ? 1.0f : -1.0f, 0.0f);
        const int frontCell = down ? 1 : 3, floorCell = 2, behindCell = down ? 3 : 1;
        LightVolume light;
        light.reset(grid);
        const glm::vec4 lobe = toVec4(sh::cosineLobe(towardFloor)) / shading::kPi;
        light.r[grid.index({1, frontCell, 1})] = light.g[grid.index({1, frontCell, 1})] =
            light.b[grid.index({1, frontCell, 1})] = lobe;
        PropagationOptions options;
        options.bounces = false;
        LightVolume once;
        CpuPropagator::step(light, geometry, options, once);
        EXPECT_GT(flux(once, {1, floorCell, 1}), 0.1f * lobe.x);  // the floor's cell is lit
        // Two steps: the floor stops the light crossing it, all but what crosses its plane
        // obliquely: a blocker is a cosine in the direction of travel (seed 000), and the flux
        // toward the 4 side faces beyond travels 26.6 degrees off the normal (0.89 blocked).
        LightVolume twice;
        CpuPropagator::step(once, geometry, options, twice);
        float behind = 0.0f, reached = 0.0f;
        for (int z = 0; z < 4; ++z)
            for (int x = 0; x < 4; ++x) {
                behind += std::abs(flux(twice, {x, behindCell, z}));
                reached += flux(once, {x, floorCell, z});
            }
        EXPECT_LT(behind, 0.05f * reached);
    }
}

TEST(LpvStaticBlockers, MergingKeepsAPlanesBlockerThatHasNoConstantTerm) {
    // The voxelizer's blocker of one plane is exactly <n.w>_+: c0 = 0 (volumes/blocker_sh.h).
    const glm::vec4 plane = blockerSH(0.0f, glm::vec3(0.0f, 1.0f, 0.0f), BlockerFit::PlaneExact);
    ASSERT_EQ(plane.x, 0.0f);
    EXPECT_EQ(mergeBlockers(glm::vec4(0.0f), plane), plane);
    EXPECT_EQ(mergeBlockers(plane, glm::vec4(0.0f)), plane);
    // Facing the same way, the stronger one stays: a full plane over a weak cosine-lobe surfel.
    const glm::vec4 weak = 0.1f * glm::vec4(1.0f, -1.0f, 0.0f, 0.0f);
    EXPECT_EQ(mergeBlockers(weak, plane), plane);
    EXPECT_NEAR(evaluateBlocker(mergeBlockers(weak, plane), glm::vec3(0.0f, 1.0f, 0.0f)), 1.0f, 1e-5f);
}
