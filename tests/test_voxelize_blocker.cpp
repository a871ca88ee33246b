// Blocker SH, albedo, normals, cascade levels and occupancy culling (active bricks).
#include <cmath>
#include <set>
#include <tuple>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "scenes/primitives.h"
#include "volumes/geometry_volume.h"

using namespace voxgi;

namespace {

Scene sceneWith(const std::vector<Mesh>& meshes, std::vector<Material> materials = {Material{}}) {
    Scene scene;
    scene.materials = std::move(materials);
    scene.meshes = meshes;
    return scene;
}

SparseGeometryVolume voxelize(const Scene& scene, float h, int levels = 1, BlockerFit fit = BlockerFit::PlaneExact) {
    VoxelizeSettings settings;
    settings.voxelSize = h;
    settings.levels = levels;
    settings.blockerFit = fit;
    return voxelizeScene(scene, settings);
}

// A wall z = 0.3 facing +z, from -1 to 2 in x and y: voxels of layer 1 (h = 0.25) are crossed
// through their middle.
Mesh wall() {
    return makeQuad({glm::vec3(-1, -1, 0.3f), glm::vec3(2, -1, 0.3f), glm::vec3(2, 2, 0.3f), glm::vec3(-1, 2, 0.3f)}, 0);
}

const glm::vec3 kAxes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};

}  // namespace

TEST(Blocker, ShBasisFollowsTheStatedConvention) {
    // c = (0, 0, 1/Y1, 0) is the function z: 1 toward +z, 0 sideways, clamped to 0 behind.
    glm::vec4 z(0.0f, 0.0f, 1.0f / kShY1, 0.0f);
    EXPECT_NEAR(evaluateBlocker(z, {0, 0, 1}), 1.0f, 1e-6f);
    EXPECT_NEAR(evaluateBlocker(z, {1, 0, 0}), 0.0f, 1e-6f);
    EXPECT_EQ(evaluateBlocker(z, {0, 0, -1}), 0.0f);
    EXPECT_NEAR(evaluateBlocker({0.0f, -1.0f / kShY1, 0.0f, 0.0f}, {0, 1, 0}), 1.0f, 1e-6f);  // Y1-1 = -k y
    EXPECT_NEAR(evaluateBlocker({0.0f, 0.0f, 0.0f, -1.0f / kShY1}, {1, 0, 0}), 1.0f, 1e-6f);  // Y11 = -k x
    EXPECT_NEAR(evaluateBlocker({0.5f / kShY00, 0.0f, 0.0f, 0.0f}, {0.3f, -0.8f, 0.52f}), 0.5f, 1e-6f);
}

TEST(Blocker, FullWallBlocksAlongItsNormalAndNotAlongItsPlane) {
    SparseGeometryVolume v = voxelize(sceneWith({wall()}), 0.25f);
    for (glm::ivec3 c : {glm::ivec3(0, 0, 1), glm::ivec3(3, 5, 1), glm::ivec3(-2, 4, 1)}) {
        glm::vec4 sh = v.blockerSH(c);
        EXPECT_NEAR(evaluateBlocker(sh, {0, 0, 1}), 1.0f, 1e-4f);
        EXPECT_NEAR(evaluateBlocker(sh, {1, 0, 0}), 0.0f, 1e-4f);
        EXPECT_NEAR(evaluateBlocker(sh, {0, -1, 0}), 0.0f, 1e-4f);
        EXPECT_EQ(evaluateBlocker(sh, {0, 0, -1}), 0.0f);
        // In between it follows the clamped cosine.
        EXPECT_NEAR(evaluateBlocker(sh, glm::normalize(glm::vec3(1, 0, 1))), std::sqrt(0.5f), 1e-4f);
        EXPECT_NEAR(glm::length(v.normal(c) - glm::vec3(0, 0, 1)), 0.0f, 1e-5f);
    }
    // Empty voxels, next to the wall or far away, block nothing.
    for (glm::ivec3 c : {glm::ivec3(0, 0, 0), glm::ivec3(0, 0, 2), glm::ivec3(40, 40, 40)}) {
        EXPECT_FALSE(v.occupied(c));
        for (const glm::vec3& w : kAxes) EXPECT_EQ(evaluateBlocker(v.blockerSH(c), w), 0.0f);
    }
    // The seeds' literal projection of the clamped cosine: 3/4 along the normal, 1/4 in plane.
    SparseGeometryVolume p = voxelize(sceneWith({wall()}), 0.25f, 1, BlockerFit::Projection);
    EXPECT_NEAR(evaluateBlocker(p.blockerSH({0, 0, 1}), {0, 0, 1}), 0.75f, 1e-4f);
    EXPECT_NEAR(evaluateBlocker(p.blockerSH({0, 0, 1}), {1, 0, 0}), 0.25f, 1e-4f);
}

TEST(Blocker, HalfCoveredVoxelBlocksHalf) {
    // The wall ends at x = 0.125, halfway through voxel column 0.
    Mesh half = makeQuad({glm::vec3(-1, -1, 0.3f), glm::vec3(0.125f, -1, 0.3f), glm::vec3(0.125f, 2, 0.3f),
                          glm::vec3(-1, 2, 0.3f)}, 0);
    SparseGeometryVolume v = voxelize(sceneWith({half}), 0.25f);
    EXPECT_NEAR(evaluateBlocker(v.blockerSH({0, 2, 1}), {0, 0, 1}), 0.5f, 1e-4f);
    EXPECT_NEAR(evaluateBlocker(v.blockerSH({-1, 2, 1}), {0, 0, 1}), 1.0f, 1e-4f);
}

TEST(Blocker, ClosedObjectBlocksItsMeanSilhouetteInEveryDirection) {
    // A cube of side h/2 inside one voxel: surface 6/4 of a face, net normal 0, so by Cauchy's
    // formula it blocks (6/4)/4 = 0.375 from every direction.
    glm::mat4 t = glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(0.5f)), glm::vec3(0.5f));
    SparseGeometryVolume v = voxelize(sceneWith({makeBox(t, 0)}), 1.0f);
    ASSERT_EQ(v.activeVoxelCount(), 1u);
    glm::vec4 sh = v.blockerSH({0, 0, 0});
    for (const glm::vec3& w : kAxes) EXPECT_NEAR(evaluateBlocker(sh, w), 0.375f, 1e-5f);
    EXPECT_NEAR(evaluateBlocker(sh, glm::normalize(glm::vec3(1, -2, 3))), 0.375f, 1e-5f);
    EXPECT_NEAR(glm::length(v.normal({0, 0, 0})), 0.0f, 1e-5f);
}

TEST(Albedo, AreaWeightedAcrossMaterialsAndTextured) {
    Material red, green, textured;
    red.albedo = {1, 0, 0};
    green.albedo = {0, 1, 0};
    textured.albedo = {0.5f, 0.5f, 0.5f};
    textured.albedoTexture = 0;
    // Red up to x = 0.55, green beyond: voxel column 5 ([0.5, 0.6]) sees half of each.
    Mesh r = makeQuad({glm::vec3(0, 0, 0.05f), glm::vec3(0.55f, 0, 0.05f), glm::vec3(0.55f, 1, 0.05f), glm::vec3(0, 1, 0.05f)}, 0);
    Mesh g = makeQuad({glm::vec3(0.55f, 0, 0.05f), glm::vec3(1, 0, 0.05f), glm::vec3(1, 1, 0.05f), glm::vec3(0.55f, 1, 0.05f)}, 1);
    // A 2x1 texture, white on the left half (u < 0.5) and black on the right, at z = 0.55.
    Mesh t = makeQuad({glm::vec3(0, 0, 0.55f), glm::vec3(1, 0, 0.55f), glm::vec3(1, 1, 0.55f), glm::vec3(0, 1, 0.55f)}, 2);
    t.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    Scene scene = sceneWith({r, g, t}, {red, green, textured});
    Texture tex;
    tex.width = 2;
    tex.height = 1;
    tex.rgba = {255, 255, 255, 255, 0, 0, 0, 255};
    tex.averageLinear = glm::vec3(0.5f);
    scene.textures.push_back(tex);
    SparseGeometryVolume v = voxelize(scene, 0.1f);
    EXPECT_NEAR(glm::length(v.albedo({2, 4, 0}) - glm::vec3(1, 0, 0)), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::length(v.albedo({8, 4, 0}) - glm::vec3(0, 1, 0)), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::length(v.albedo({5, 4, 0}) - glm::vec3(0.5f, 0.5f, 0)), 0.0f, 1e-4f);
    EXPECT_NEAR(glm::length(v.albedo({2, 4, 5}) - glm::vec3(0.5f)), 0.0f, 1e-4f);
    EXPECT_NEAR(glm::length(v.albedo({7, 4, 5})), 0.0f, 1e-4f);
}

TEST(Albedo, IsTheDiffuseAlbedo) {
    // What a voxel bounces is the Lambert part of its material: metals and the specular coat's
    // share go to the GGX lobe.
    Material coated;
    coated.albedo = {0.8f, 0.6f, 0.4f};
    coated.metallic = 0.25f;
    coated.specular = 0.5f;
    Mesh wall =
        makeQuad({glm::vec3(0, 0, 0.05f), glm::vec3(1, 0, 0.05f), glm::vec3(1, 1, 0.05f), glm::vec3(0, 1, 0.05f)}, 0);
    SparseGeometryVolume v = voxelize(sceneWith({wall}, {coated}), 0.1f);
    EXPECT_NEAR(glm::length(v.albedo({4, 4, 0}) - 0.75f * 0.5f * coated.albedo), 0.0f, 1e-4f);
}

TEST(Levels, CoarseLevelsNestAndMatchDirectVoxelization) {
    glm::mat4 t = glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(0.43f, 0.51f, 0.47f)), 0.7f, glm::vec3(1, 1, 0));
    Scene scene = sceneWith({makeSphere(glm::scale(t, glm::vec3(0.3f)), 0, 24), makeBox(glm::scale(t, glm::vec3(0.5f, 0.2f, 0.3f)), 0)});
    const float h = 0.02f;
    SparseGeometryVolume v = voxelize(scene, h, 3);
    ASSERT_EQ(v.levelCount(), 3);
    for (int level = 1; level < 3; ++level) {
        EXPECT_FLOAT_EQ(v.voxelSize(level), h * float(1 << level));
        SparseGeometryVolume direct = voxelize(scene, h * float(1 << level));
        EXPECT_EQ(v.activeVoxelCount(level), direct.activeVoxelCount());
        IndexBox b = direct.indexBounds();
        int mismatches = 0;
        float worstBlocker = 0.0f;
        for (int z = b.min.z - 1; z <= b.max.z + 1; ++z)
            for (int y = b.min.y - 1; y <= b.max.y + 1; ++y)
                for (int x = b.min.x - 1; x <= b.max.x + 1; ++x) {
                    glm::ivec3 c(x, y, z);
                    mismatches += v.occupied(c, level) != direct.occupied(c);
                    if (direct.occupied(c))
                        for (const glm::vec3& w : kAxes)
                            worstBlocker = std::max(worstBlocker, std::abs(evaluateBlocker(v.blockerSH(c, level), w) -
                                                                           evaluateBlocker(direct.blockerSH(c), w)));
                }
        EXPECT_EQ(mismatches, 0) << "level " << level;
        EXPECT_LT(worstBlocker, 1e-3f) << "level " << level;
    }
}

TEST(Bricks, ActiveBricksCoverOccupancyAndDilation) {
    Scene scene = sceneWith({makeSphere(glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(0.3f)), glm::vec3(0.25f)), 0)});
    const float h = 0.02f;
    SparseGeometryVolume v = voxelize(scene, h);
    for (int k : {0, 1, 3}) {
        std::vector<Brick> bricks = v.activeBricks(0, k);
        std::set<std::tuple<int, int, int>> set;
        for (const Brick& b : bricks) {
            EXPECT_EQ(b.origin % 8, glm::ivec3(0));
            EXPECT_NEAR(glm::length(b.worldMin - glm::vec3(b.origin) * h), 0.0f, 1e-5f);
            EXPECT_NEAR(glm::length(b.worldMax - glm::vec3(b.origin + 8) * h), 0.0f, 1e-5f);
            set.insert({b.origin.x, b.origin.y, b.origin.z});
        }
        EXPECT_EQ(set.size(), bricks.size());
        // Expected: the bricks holding any voxel within Chebyshev distance k of an occupied one.
        std::set<std::tuple<int, int, int>> expected;
        IndexBox box = v.indexBounds();
        for (int z = box.min.z; z <= box.max.z; ++z)
            for (int y = box.min.y; y <= box.max.y; ++y)
                for (int x = box.min.x; x <= box.max.x; ++x) {
                    if (!v.occupied({x, y, z})) continue;
                    for (int dz = -k; dz <= k; ++dz)
                        for (int dy = -k; dy <= k; ++dy)
                            for (int dx = -k; dx <= k; ++dx) {
                                glm::ivec3 o = (glm::ivec3(x + dx, y + dy, z + dz) >> 3) * 8;
                                expected.insert({o.x, o.y, o.z});
                            }
                }
        EXPECT_EQ(set, expected) << "dilation " << k;
    }
    EXPECT_GT(v.activeBricks(0, 3).size(), v.activeBricks(0, 0).size());
}
