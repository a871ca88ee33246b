// Voxelizer on analytic shapes (exact voxel counts or stated bounds, watertight occupancy,
// conserved area) and on bad input (skipped and counted triangles, empty meshes, refusals).
#include <cmath>
#include <cstdio>
#include <deque>
#include <limits>
#include <random>
#include <set>
#include <tuple>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "scenes/errors.h"
#include "scenes/primitives.h"
#include "shaders/shared/constants.h"
#include "support/test_support.h"
#include "volumes/geometry_volume.h"
#include "volumes/triangle_box.h"

using namespace voxgi;

namespace {

Scene sceneWith(const std::vector<Mesh>& meshes) {
    Scene scene;
    scene.materials.push_back(Material{});
    scene.meshes = meshes;
    return scene;
}

SparseGeometryVolume voxelize(const Scene& scene, float voxelSize, BlockerFit fit = BlockerFit::Projection) {
    VoxelizeSettings settings;
    settings.voxelSize = voxelSize;
    settings.blockerFit = fit;
    return voxelizeScene(scene, settings);
}


// Clipped area summed over voxels, recovered from the Projection fit's constant term.
double totalArea(const SparseGeometryVolume& v) {
    double h = v.voxelSize(), sum = 0.0;
    for (const glm::ivec3& c : test::occupiedVoxels(v)) sum += 4.0 * kShY00 * v.blockerSH(c)[0] * h * h;
    return sum;
}

// True when a 6-connected walk through empty voxels from outside the bounds reaches `inside`.
bool leaksTo(const SparseGeometryVolume& v, const glm::ivec3& inside) {
    IndexBox b = v.indexBounds();
    glm::ivec3 lo = b.min - 1, hi = b.max + 1, size = hi - lo + 1;
    std::vector<char> seen(std::size_t(size.x) * size.y * size.z, 0);
    auto id = [&](const glm::ivec3& c) { return (std::size_t(c.z - lo.z) * size.y + (c.y - lo.y)) * size.x + (c.x - lo.x); };
    std::deque<glm::ivec3> queue{lo};
    seen[id(lo)] = 1;
    const glm::ivec3 steps[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    while (!queue.empty()) {
        glm::ivec3 c = queue.front();
        queue.pop_front();
        if (c == inside) return true;
        for (const glm::ivec3& s : steps) {
            glm::ivec3 n = c + s;
            if (glm::any(glm::lessThan(n, lo)) || glm::any(glm::greaterThan(n, hi)) || seen[id(n)] || v.occupied(n)) continue;
            seen[id(n)] = 1;
            queue.push_back(n);
        }
    }
    return false;
}

}  // namespace

TEST(TriangleBox, SeparatingAxesAgreeWithClipping) {
    // Independent check of the SAT on random triangles: a non-empty clip means overlap, and an
    // overlap means the clip against a slightly grown box is non-empty.
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-1.5f, 1.5f);
    int overlaps = 0;
    for (int i = 0; i < 20000; ++i) {
        glm::vec3 a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng)), c(u(rng), u(rng), u(rng));
        bool sat = triangleOverlapsBox(a, b, c, glm::vec3(0.0f), glm::vec3(0.5f));
        bool clipped = polygonMoments(clipTriangleToBox(a, b, c, glm::vec3(-0.5f), glm::vec3(0.5f))).area > 0.0f;
        bool grown = clipTriangleToBox(a, b, c, glm::vec3(-0.5001f), glm::vec3(0.5001f)).count > 0;
        if (clipped) {
            EXPECT_TRUE(sat) << i;
        }
        if (sat) {
            EXPECT_TRUE(grown) << i;
        }
        overlaps += sat;
    }
    EXPECT_GT(overlaps, 2000);
}

TEST(TriangleBox, SlabsInAnyAxisOrderCutTheSamePiece) {
    // The voxelizer clips a triangle to its row, the row to a column and the column to a voxel,
    // along the triangle's own axis order; the piece must be the one a box clip gives.
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(-1.5f, 1.5f);
    const int orders[3][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}};
    int cut = 0;
    for (int i = 0; i < 20000; ++i) {
        glm::vec3 a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng)), c(u(rng), u(rng), u(rng));
        const PolygonMoments box = polygonMoments(clipTriangleToBox(a, b, c, glm::vec3(-0.5f), glm::vec3(0.5f)));
        for (const auto& order : orders) {
            ClipPolygon piece;
            piece.v[0] = a;
            piece.v[1] = b;
            piece.v[2] = c;
            piece.count = 3;
            for (int axis : order) clipToSlab(piece, axis, -0.5f, 0.5f);
            const PolygonMoments m = polygonMoments(piece);
            ASSERT_NEAR(m.area, box.area, 1e-5f * (1.0f + box.area)) << i;
            if (box.area > 1e-3f) {
                EXPECT_LT(glm::length(m.centroid - box.centroid), 1e-4f) << i;
            }
        }
        cut += box.area > 0.0f;
    }
    EXPECT_GT(cut, 2000);
}

TEST(Voxelize, AxisAlignedBoxShellIsExactAndClosed) {
    // Faces at 0.05 and 0.95 run through the middle of voxel layers 0 and 9: the shell of the
    // 10^3 block, 10^3 - 8^3 voxels.
    glm::mat4 t = glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(0.5f)), glm::vec3(0.9f));
    SparseGeometryVolume v = voxelize(sceneWith({makeBox(t, 0)}), 0.1f);
    EXPECT_EQ(v.activeVoxelCount(), 488u);
    for (const glm::ivec3& c : test::occupiedVoxels(v)) {
        EXPECT_TRUE(glm::all(glm::greaterThanEqual(c, glm::ivec3(0))) && glm::all(glm::lessThanEqual(c, glm::ivec3(9))));
        EXPECT_TRUE(c.x == 0 || c.x == 9 || c.y == 0 || c.y == 9 || c.z == 0 || c.z == 9);
    }
    EXPECT_FALSE(leaksTo(v, {5, 5, 5}));
    EXPECT_NEAR(totalArea(v), 6.0 * 0.81, 1e-4);
    // A face-interior voxel holds a full wall: unit coverage along the outward normal.
    EXPECT_NEAR(glm::length(v.normal({5, 5, 0}) - glm::vec3(0, 0, -1)), 0.0f, 1e-5f);
}

TEST(Voxelize, SphereStaysWithinTheShellBoundsAndClosed) {
    const float r = 0.4f, h = 0.025f;
    const glm::vec3 center(0.51f, 0.49f, 0.505f);
    Scene scene = sceneWith({makeSphere(glm::scale(glm::translate(glm::mat4(1.0f), center), glm::vec3(r)), 0, 32)});
    SparseGeometryVolume v = voxelize(scene, h);
    // The mesh lies between the sphere and the sphere shrunk by the faces' sagitta.
    const float inner = r * std::cos(shading::kPi / 16.0f), slack = 1e-4f * h;
    std::set<std::tuple<int, int, int>> occupied;
    for (const glm::ivec3& c : test::occupiedVoxels(v)) occupied.insert({c.x, c.y, c.z});
    int required = 0;
    for (int z = -2; z < 42; ++z)
        for (int y = -2; y < 42; ++y)
            for (int x = -2; x < 42; ++x) {
                glm::vec3 lo = glm::vec3(x, y, z) * h, hi = lo + h;
                float dmin = glm::length(glm::clamp(center, lo, hi) - center);
                float dmax = glm::length(glm::max(glm::abs(lo - center), glm::abs(hi - center)));
                bool on = occupied.count({x, y, z}) != 0;
                if (on) {
                    EXPECT_TRUE(dmin <= r + slack && dmax >= inner - slack) << x << " " << y << " " << z;
                }
                if (dmin < inner - slack && dmax > r + slack) {
                    ++required;
                    EXPECT_TRUE(on) << "hole at " << x << " " << y << " " << z;
                }
            }
    EXPECT_GT(required, 3000);
    EXPECT_EQ(v.activeVoxelCount(), occupied.size());  // nothing outside the scanned block
    EXPECT_FALSE(leaksTo(v, glm::ivec3(center / h)));
}

TEST(Voxelize, PlaneOnVoxelBoundariesTouchesBothLayersAndCountsAreaOnce) {
    // z = 0.5 is the face between layers 3 and 4 (h = 0.125, exact in binary); x and y run from
    // face 0 to face 8. Closed voxel boxes: columns -1..8 in x and y, layers 3 and 4.
    Mesh quad = makeQuad({glm::vec3(0, 0, 0.5f), glm::vec3(1, 0, 0.5f), glm::vec3(1, 1, 0.5f), glm::vec3(0, 1, 0.5f)}, 0);
    SparseGeometryVolume v = voxelize(sceneWith({quad}), 0.125f);
    EXPECT_EQ(v.activeVoxelCount(), 10u * 10u * 2u);
    IndexBox b = v.indexBounds();
    EXPECT_EQ(b.min, glm::ivec3(-1, -1, 3));
    EXPECT_EQ(b.max, glm::ivec3(8, 8, 4));
    EXPECT_NEAR(totalArea(v), 1.0, 1e-5);
    // The area sits in exactly one layer: each interior column carries coverage 1 in total.
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x)
            EXPECT_NEAR(v.normal({x, y, 3}).z + v.normal({x, y, 4}).z, 1.0f, 1e-5f);
}

TEST(Voxelize, TiltedTriangleMatchesIndependentClippingAndDenseSamples) {
    const float h = 0.1f;
    glm::vec3 a(0.013f, 0.021f, 0.37f), b(1.31f, 0.27f, 0.05f), c(0.42f, 1.17f, 0.93f);
    SparseGeometryVolume v = voxelize(sceneWith({makePolygons({a, b, c}, {{0, 1, 2}}, 0)}), h);
    // Bounds: every voxel the exact clip gives area is occupied; every occupied voxel's box,
    // grown by a hair, still meets the triangle.
    std::size_t withArea = 0, occupied = 0;
    for (int z = -2; z < 12; ++z)
        for (int y = -2; y < 14; ++y)
            for (int x = -2; x < 15; ++x) {
                glm::vec3 lo = glm::vec3(x, y, z) * h, hi = lo + h;
                bool area = polygonMoments(clipTriangleToBox(a, b, c, lo, hi)).area > 0.0f;
                bool near = clipTriangleToBox(a, b, c, lo - 1e-4f * h, hi + 1e-4f * h).count > 0;
                bool on = v.occupied({x, y, z});
                if (area) {
                    EXPECT_TRUE(on) << x << " " << y << " " << z;
                }
                if (on) {
                    EXPECT_TRUE(near) << x << " " << y << " " << z;
                }
                withArea += area;
                occupied += on;
            }
    EXPECT_EQ(occupied, v.activeVoxelCount());
    EXPECT_GE(occupied, withArea);
    EXPECT_LE(occupied, withArea + withArea / 10);  // touch-only voxels: edges and corners
    // No holes: dense samples on the triangle all land in occupied voxels.
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int i = 0; i < 100000; ++i) {
        float s = u(rng), t = u(rng);
        if (s + t > 1.0f) s = 1.0f - s, t = 1.0f - t;
        glm::vec3 p = a + s * (b - a) + t * (c - a);
        ASSERT_TRUE(v.occupied(v.voxelAt(p))) << p.x << " " << p.y << " " << p.z;
    }
    EXPECT_NEAR(totalArea(v), 0.5 * glm::length(glm::cross(b - a, c - a)), 1e-5);
}

TEST(Voxelize, BadTrianglesAreSkippedAndCounted) {
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    Mesh m;
    m.positions = {{0.05f, 0.05f, 0.05f}, {0.35f, 0.05f, 0.05f}, {0.05f, 0.35f, 0.05f},  // good
                   {0.5f, 0.5f, 0.5f}, {0.7f, 0.5f, 0.5f}, {0.9f, 0.5f, 0.5f},        // collinear
                   {nan, 0.0f, 0.0f}, {0.0f, inf, 0.0f}};
    m.indices = {0, 1, 2, 3, 4, 5, 0, 0, 1, 0, 1, 99, 0, 1, 6, 7, 1, 2};
    m.materialIds.assign(6, 0);
    VoxelizeSettings settings;
    settings.voxelSize = 0.1f;
    SparseGeometryVolume v = voxelizeScene(sceneWith({m}), settings);
    EXPECT_EQ(v.stats().triangles, 6u);
    EXPECT_EQ(v.stats().trianglesUsed, 1u);
    EXPECT_EQ(v.stats().skippedDegenerate, 3u);  // collinear, repeated index, index out of range
    EXPECT_EQ(v.stats().skippedNonFinite, 2u);
    Mesh good;
    good.positions = {m.positions[0], m.positions[1], m.positions[2]};
    good.indices = {0, 1, 2};
    good.materialIds = {0};
    EXPECT_EQ(v.activeVoxelCount(), voxelizeScene(sceneWith({good}), settings).activeVoxelCount());
    for (const glm::ivec3& c : test::occupiedVoxels(v)) {
        glm::vec4 sh = v.blockerSH(c);
        for (int i = 0; i < 4; ++i) EXPECT_TRUE(std::isfinite(sh[i]));
    }
}

TEST(Voxelize, EmptySceneGivesAnEmptyVolume) {
    VoxelizeSettings settings;
    settings.voxelSize = 0.1f;
    settings.levels = 2;
    SparseGeometryVolume v = voxelizeScene(Scene{}, settings);
    EXPECT_EQ(v.levelCount(), 2);
    EXPECT_EQ(v.activeVoxelCount(0), 0u);
    EXPECT_TRUE(v.indexBounds().empty());
    EXPECT_TRUE(v.activeBricks(0, 2).empty());
    EXPECT_EQ(v.blockerSH({0, 0, 0}), glm::vec4(0.0f));
}

TEST(Voxelize, AbsurdResolutionIsRefusedBeforeAllocating) {
    Scene scene = test::cornellBox();
    VoxelizeSettings settings;
    settings.voxelSize = 1e-4f;  // ~2e8 voxels on the 0.55 m box
    try {
        voxelizeScene(scene, settings);
        FAIL() << "expected a refusal";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("--max-voxels"), std::string::npos) << e.what();
    }
    settings.voxelSize = 1e-6f;  // below what OpenVDB transforms accept
    EXPECT_THROW(voxelizeScene(scene, settings), InputError);
    settings.voxelSize = 0.0f;
    EXPECT_THROW(voxelizeScene(scene, settings), InputError);
    settings.voxelSize = std::numeric_limits<float>::quiet_NaN();
    EXPECT_THROW(voxelizeScene(scene, settings), InputError);
    // The estimate bounds the real count from above on ordinary input.
    settings.voxelSize = 0.02f;
    SparseGeometryVolume v = voxelizeScene(scene, settings);
    EXPECT_GE(v.stats().estimatedVoxels, v.activeVoxelCount());
}
