// The compact in-memory geometry set: attributes stored for active voxels only and found
// through the occupancy topology (leaf base index + active bits below the voxel), albedo halves
// within their stated bound, the dense file grids agreeing with the accessors, memoryBytes
// counting every array, a file whose blocker contradicts its normal grid refused, and the
// projected coverage: the area seen along each axis, estimated for older files.
//
// This file builds OpenVDB grids itself; the voxgi_volumes objects are compiled with
// OPENVDB_USE_DELAYED_LOADING (from OpenVDB's CMake target), which changes OpenVDB's class
// layouts, so it is set here too.
#ifndef OPENVDB_USE_DELAYED_LOADING
#define OPENVDB_USE_DELAYED_LOADING
#endif

#include <cmath>
#include <map>
#include <random>
#include <tuple>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>
#include <openvdb/openvdb.h>

#include "scenes/errors.h"
#include "support/test_support.h"
#include "scenes/primitives.h"
#include "volumes/blocker_sh.h"
#include "volumes/detail/geometry_grids.h"
#include "volumes/geometry_volume.h"

using namespace voxgi;

namespace {

constexpr float kHalfRelative = 1.0f / 2048.0f;  // 2^-11
constexpr float kHalfSubnormal = 2.9802322e-08f;  // 2^-25

struct Expected {
    glm::vec3 albedo;
    glm::vec3 normal;  // area * unit normal (h = 1)
};

using VoxelKey = std::tuple<int, int, int>;

// One small triangle strictly inside each chosen voxel (h = 1), each with its own material,
// randomly oriented: every voxel's attributes are distinct, so an index pointing at another
// voxel's slot shows. Leaves are full, sparse or single-voxel.
Scene scatteredTriangles(std::map<VoxelKey, Expected>& expected) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<glm::ivec3> voxels;
    for (int x = 0; x < 8; ++x)
        for (int y = 0; y < 8; ++y)
            for (int z = 0; z < 8; ++z) voxels.push_back({x, y, z});  // a full leaf
    for (int i = 0; i < 3000; ++i)  // sparse leaves, negative coordinates included
        voxels.push_back({int(unit(rng) * 64.0f) - 32, int(unit(rng) * 64.0f) - 32, int(unit(rng) * 24.0f) + 16});
    voxels.push_back({-100, 37, 5});  // a leaf with one voxel
    voxels.push_back({7, 15, 23});    // the last offset of its leaf

    Scene scene;
    Mesh mesh;
    for (const glm::ivec3& v : voxels) {
        if (expected.count({v.x, v.y, v.z})) continue;
        const glm::vec3 center = glm::vec3(v) + 0.5f;
        // A random frame: the triangle lies in the plane spanned by u, w at radius 0.3 < 0.5.
        glm::vec3 n = glm::normalize(glm::vec3(unit(rng) - 0.5f, unit(rng) - 0.5f, unit(rng) - 0.5f) + 1e-3f);
        glm::vec3 u = glm::normalize(glm::cross(n, std::abs(n.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0)));
        glm::vec3 w = glm::cross(n, u);
        const float r = 0.3f;
        glm::vec3 a = center + r * u, b = center + r * (-0.5f * u + 0.866f * w), c = center + r * (-0.5f * u - 0.866f * w);
        auto base = std::uint32_t(mesh.positions.size());
        mesh.positions.insert(mesh.positions.end(), {a, b, c});
        mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2});
        mesh.materialIds.push_back(std::uint32_t(scene.materials.size()));
        Material m;
        m.albedo = glm::vec3(unit(rng), unit(rng), unit(rng));
        scene.materials.push_back(m);
        glm::vec3 cr = glm::cross(b - a, c - a);
        expected[{v.x, v.y, v.z}] = {m.albedo, 0.5f * cr};
    }
    scene.meshes.push_back(std::move(mesh));
    return scene;
}

SparseGeometryVolume voxelizeUnit(const Scene& scene, int levels = 1) {
    VoxelizeSettings settings;
    settings.voxelSize = 1.0f;
    settings.levels = levels;
    return voxelizeScene(scene, settings);
}

void expectAlbedoWithinHalfBound(const glm::vec3& got, const glm::vec3& want) {
    for (int c = 0; c < 3; ++c)
        EXPECT_LE(std::abs(got[c] - want[c]), kHalfRelative * std::abs(want[c]) + 1e-6f * std::abs(want[c]) + kHalfSubnormal)
            << got[c] << " vs " << want[c];
}

}  // namespace

TEST(VolumeCompact, AlbedoHalvesStayWithinTheStatedBound) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> exponent(-30.0f, 16.0f);
    for (int i = 0; i < 200000; ++i) {
        const float v = std::exp2(exponent(rng));
        const glm::vec3 got = detail::fromHalves(detail::toHalves(glm::vec3(v, 0.5f * v, v / 3.0f)));
        const glm::vec3 want(v, 0.5f * v, v / 3.0f);
        for (int c = 0; c < 3; ++c) {
            const float bound = std::abs(want[c]) >= 6.1035156e-05f ? kHalfRelative * std::abs(want[c]) : kHalfSubnormal;
            ASSERT_LE(std::abs(got[c] - want[c]), bound) << want[c];
        }
    }
    // Exact values the tests and materials use survive unchanged; the range saturates.
    for (float v : {0.0f, 1.0f, 0.5f, 0.25f, 0.75f})
        EXPECT_EQ(detail::fromHalves(detail::toHalves(glm::vec3(v))), glm::vec3(v));
    EXPECT_EQ(detail::fromHalves(detail::toHalves(glm::vec3(1e9f))), glm::vec3(65504.0f));
}

TEST(VolumeCompact, EveryVoxelReadsItsOwnAttributes) {
    std::map<VoxelKey, Expected> expected;
    SparseGeometryVolume v = voxelizeUnit(scatteredTriangles(expected));
    ASSERT_EQ(v.activeVoxelCount(), expected.size());
    for (const auto& [key, e] : expected) {
        const glm::ivec3 c(std::get<0>(key), std::get<1>(key), std::get<2>(key));
        ASSERT_TRUE(v.occupied(c));
        expectAlbedoWithinHalfBound(v.albedo(c), e.albedo);
        EXPECT_LE(glm::length(v.normal(c) - e.normal), 1e-5f * glm::length(e.normal));
        // One flat piece: the plane-exact blocker is its coverage along the normal, 0 behind.
        const glm::vec4 sh = v.blockerSH(c);
        EXPECT_EQ(sh, blockerSH(sh[0], v.normal(c), BlockerFit::PlaneExact));
        const glm::vec3 n = glm::normalize(e.normal);
        EXPECT_NEAR(evaluateBlocker(sh, n), glm::length(e.normal), 1e-5f);
        EXPECT_EQ(evaluateBlocker(sh, -n), 0.0f);
    }
    // Empty voxels inside occupied leaves and outside them read zero.
    for (const glm::ivec3& c : {glm::ivec3(-100, 37, 4), glm::ivec3(-99, 37, 5), glm::ivec3(500, 0, 0)}) {
        EXPECT_FALSE(v.occupied(c));
        EXPECT_EQ(v.albedo(c), glm::vec3(0.0f));
        EXPECT_EQ(v.normal(c), glm::vec3(0.0f));
        EXPECT_EQ(v.blockerSH(c), glm::vec4(0.0f));
    }
}

TEST(VolumeCompact, FileGridsAreDenseCopiesOfTheAccessors) {
    std::map<VoxelKey, Expected> expected;
    SparseGeometryVolume v = voxelizeUnit(scatteredTriangles(expected), 2);
    openvdb::GridPtrVec grids = detail::expandGrids(v.grids());
    ASSERT_EQ(grids.size(), 16u);
    for (int level = 0; level < 2; ++level) {
        auto find = [&](const std::string& base) {
            for (const auto& g : grids)
                if (g->getName() == gridName(base, level)) return g;
            ADD_FAILURE() << "no grid " << gridName(base, level);
            return openvdb::GridBase::Ptr();
        };
        auto occupancy = openvdb::gridPtrCast<openvdb::BoolGrid>(find("occupancy"));
        auto albedo = openvdb::gridPtrCast<openvdb::Vec3fGrid>(find("albedo"));
        auto normal = openvdb::gridPtrCast<openvdb::Vec3fGrid>(find("normal"));
        auto projected = openvdb::gridPtrCast<openvdb::Vec3fGrid>(find("projected_coverage"));
        ASSERT_TRUE(occupancy && albedo && normal && projected);
        EXPECT_EQ(occupancy->activeVoxelCount(), v.activeVoxelCount(level));
        EXPECT_EQ(albedo->activeVoxelCount(), v.activeVoxelCount(level));
        EXPECT_EQ(normal->activeVoxelCount(), v.activeVoxelCount(level));
        EXPECT_EQ(albedo->tree().leafCount(), occupancy->tree().leafCount());
        for (int c = 0; c < 4; ++c) {
            auto b = openvdb::gridPtrCast<openvdb::FloatGrid>(find("blocker_sh" + std::to_string(c)));
            ASSERT_TRUE(b);
            EXPECT_EQ(b->activeVoxelCount(), v.activeVoxelCount(level));
            for (auto it = occupancy->cbeginValueOn(); it; ++it) {
                const glm::ivec3 ijk(it.getCoord().x(), it.getCoord().y(), it.getCoord().z());
                ASSERT_EQ(b->tree().getValue(it.getCoord()), v.blockerSH(ijk, level)[c]);
            }
        }
        for (auto it = occupancy->cbeginValueOn(); it; ++it) {
            const glm::ivec3 ijk(it.getCoord().x(), it.getCoord().y(), it.getCoord().z());
            const openvdb::Vec3f a = albedo->tree().getValue(it.getCoord()), n = normal->tree().getValue(it.getCoord());
            ASSERT_EQ(glm::vec3(a.x(), a.y(), a.z()), v.albedo(ijk, level));
            ASSERT_EQ(glm::vec3(n.x(), n.y(), n.z()), v.normal(ijk, level));
            const openvdb::Vec3f p = projected->tree().getValue(it.getCoord());
            ASSERT_EQ(glm::vec3(p.x(), p.y(), p.z()), v.projectedCoverage(ijk, level));
        }
        // Inactive voxels of the dense leaves hold zero, as before the compact layout.
        for (auto it = albedo->cbeginValueOff(); it; ++it) ASSERT_EQ(*it, openvdb::Vec3f(0.0f));
    }
}

TEST(VolumeCompact, MemoryCountsTreesAndArraysAndBeatsDenseGrids) {
    std::map<VoxelKey, Expected> expected;
    SparseGeometryVolume v = voxelizeUnit(scatteredTriangles(expected));
    const detail::LevelGrids& l = v.grids().levels.at(0);
    const std::uint64_t active = v.activeVoxelCount();
    const std::uint64_t arrays = l.normalC0.capacity() * sizeof(glm::vec4) +
                                 (l.albedo.capacity() + l.projected.capacity()) * sizeof(detail::Half3);
    EXPECT_EQ(l.normalC0.size(), active);
    EXPECT_EQ(l.albedo.size(), active);
    EXPECT_EQ(l.projected.size(), active);
    EXPECT_EQ(sizeof(glm::vec4) + 2 * sizeof(detail::Half3), 28u);  // bytes per active voxel
    EXPECT_GE(v.memoryBytes(), l.occupancy->memUsage() + arrays);
    EXPECT_LE(v.memoryBytes(), l.occupancy->memUsage() + arrays + 4096);
    std::uint64_t dense = 0;
    for (const auto& g : detail::expandGrids(v.grids())) dense += g->memUsage();
    EXPECT_LT(4 * v.memoryBytes(), dense);
}

// The projected coverage is the surfaces' area seen along each axis, every layer counted: a
// closed 0.5 m cube in a 1 m voxel shows 2 x 0.25 on every axis with no net normal; an open
// octagonal column of radius r and height l (vertices on the axes) none on y and 2 x 2r x l on x
// and z; a floor what its normal says. A coarser level sums its children over its larger face.
TEST(VolumeCompact, ProjectedCoverageIsTheAreaSeenAlongEachAxis) {
    Scene scene;
    scene.materials.push_back(Material{});
    scene.meshes.push_back(makeBox(glm::translate(glm::mat4(1.0f), glm::vec3(0.5f)) * glm::scale(glm::mat4(1.0f), glm::vec3(0.5f)), 0));
    const float r = 0.3f, l = 0.8f;
    std::vector<glm::vec3> ring;
    for (int k = 0; k < 8; ++k) {
        const float a = float(k) * 0.25f * 3.14159265f;
        ring.push_back({2.5f + r * std::cos(a), 0.1f, 0.5f + r * std::sin(a)});
    }
    std::vector<glm::vec3> vertices = ring;
    for (glm::vec3 v : ring) vertices.push_back(v + glm::vec3(0.0f, l, 0.0f));
    std::vector<std::vector<std::uint32_t>> sides;
    for (std::uint32_t k = 0; k < 8; ++k) sides.push_back({k, (k + 1) % 8, 8 + (k + 1) % 8, 8 + k});
    scene.meshes.push_back(makePolygons(vertices, sides, 0));
    scene.meshes.push_back(makeQuad({glm::vec3(4.2f, 0.5f, 0.2f), glm::vec3(4.2f, 0.5f, 0.8f), glm::vec3(4.8f, 0.5f, 0.8f),
                                     glm::vec3(4.8f, 0.5f, 0.2f)},
                                    0));
    const SparseGeometryVolume v = voxelizeUnit(scene, 2);
    auto expectNear = [](glm::vec3 got, glm::vec3 want, const char* what) {
        for (int a = 0; a < 3; ++a) EXPECT_NEAR(got[a], want[a], 2e-3f * (1.0f + want[a])) << what << " axis " << a;
    };
    expectNear(v.projectedCoverage({0, 0, 0}), glm::vec3(0.5f), "cube");
    expectNear(v.normal({0, 0, 0}), glm::vec3(0.0f), "cube's net normal");
    expectNear(v.projectedCoverage({2, 0, 0}), glm::vec3(4.0f * r * l, 0.0f, 4.0f * r * l), "column");
    const glm::vec3 floor = v.projectedCoverage({4, 0, 0});
    expectNear(floor, glm::abs(v.normal({4, 0, 0})), "floor");
    EXPECT_NEAR(floor.y, 0.36f, 1e-3f);
    // Level 1: voxel (0, 0, 0) holds the cube and the column's voxel (2 -> 1 is the next one).
    expectNear(v.projectedCoverage({0, 0, 0}, 1), glm::vec3(0.5f) / 4.0f, "cube at level 1");
    expectNear(v.projectedCoverage({1, 0, 0}, 1), glm::vec3(4.0f * r * l, 0.0f, 4.0f * r * l) / 4.0f, "column at level 1");
}

// A file from before the projected coverage (no projected_coverage grids) reads the estimate
// with the normals beyond the net normal spread evenly; a negative area in the grid is refused.
TEST(VolumeCompact, ProjectedCoverageFromOlderFilesAndBadValues) {
    std::map<VoxelKey, Expected> expected;
    SparseGeometryVolume v = voxelizeUnit(scatteredTriangles(expected));
    const std::string dir = test::makeTempDir("vol-compact");
    openvdb::GridPtrVec grids = detail::expandGrids(v.grids()), older;
    for (const auto& g : grids)
        if (g->getName() != "projected_coverage") older.push_back(g);
    ASSERT_EQ(older.size() + 1, grids.size());
    openvdb::io::File(dir + "/older.vdb").write(older);
    const SparseGeometryVolume r = readGeometryVolume(dir + "/older.vdb");
    for (const glm::ivec3 c : {glm::ivec3(0, 0, 0), glm::ivec3(3, 4, 5), glm::ivec3(7, 15, 23)}) {
        const glm::vec3 m = r.normal(c);
        const glm::vec3 want = isotropicProjectedCoverage(coverageFromBlocker(r.blockerSH(c)[0], m, BlockerFit::PlaneExact), m);
        for (int a = 0; a < 3; ++a) EXPECT_NEAR(r.projectedCoverage(c)[a], want[a], kHalfRelative * want[a] + kHalfSubnormal);
        // One triangle per voxel: its normals do not cancel, so the estimate is the exact |m|.
        for (int a = 0; a < 3; ++a) EXPECT_NEAR(r.projectedCoverage(c)[a], v.projectedCoverage(c)[a], 1e-3f * (1.0f + want[a]));
    }
    for (const auto& g : grids)
        if (g->getName() == "projected_coverage")
            openvdb::gridPtrCast<openvdb::Vec3fGrid>(g)->tree().setValue({7, 15, 23}, openvdb::Vec3f(0.1f, -1.0f, 0.0f));
    openvdb::io::File(dir + "/negative.vdb").write(grids);
    try {
        readGeometryVolume(dir + "/negative.vdb");
        FAIL() << "a negative area was accepted";
    } catch (const InputError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find(dir + "/negative.vdb"), std::string::npos) << message;
        EXPECT_NE(message.find("projected_coverage"), std::string::npos) << message;
        EXPECT_NE(message.find("(7, 15, 23)"), std::string::npos) << message;
    }
}

TEST(VolumeCompact, ReadingRefusesABlockerThatContradictsTheNormal) {
    std::map<VoxelKey, Expected> expected;
    SparseGeometryVolume v = voxelizeUnit(scatteredTriangles(expected));
    const std::string path = test::makeTempDir("vol-compact") + "/edited.vdb";
    openvdb::GridPtrVec grids = detail::expandGrids(v.grids());
    for (const auto& g : grids)
        if (g->getName() == "blocker_sh2") openvdb::gridPtrCast<openvdb::FloatGrid>(g)->tree().setValue({7, 15, 23}, 0.75f);
    openvdb::io::File(path).write(grids);
    try {
        readGeometryVolume(path);
        FAIL() << "an inconsistent blocker was accepted";
    } catch (const InputError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find(path), std::string::npos) << message;
        EXPECT_NE(message.find("blocker_sh2"), std::string::npos) << message;
        EXPECT_NE(message.find("(7, 15, 23)"), std::string::npos) << message;
    }
}

TEST(VolumeCompact, ActiveTilesFromOtherWritersBecomeVoxels) {
    std::map<VoxelKey, Expected> expected;
    SparseGeometryVolume v = voxelizeUnit(scatteredTriangles(expected));
    const std::string path = test::makeTempDir("vol-compact") + "/tiled.vdb";
    openvdb::GridPtrVec grids = detail::expandGrids(v.grids());
    // The full leaf at the origin stored as one active tile, as OpenVDB's prune() would.
    for (const auto& g : grids) {
        if (g->getName() != "occupancy") continue;
        auto occupancy = openvdb::gridPtrCast<openvdb::BoolGrid>(g);
        auto copy = occupancy->deepCopy();
        copy->tree().addTile(1, openvdb::Coord(0, 0, 0), true, true);
        ASSERT_EQ(copy->tree().probeConstLeaf(openvdb::Coord(0, 0, 0)), nullptr);
        occupancy->setTree(copy->treePtr());
    }
    openvdb::io::File(path).write(grids);
    SparseGeometryVolume r = readGeometryVolume(path);
    ASSERT_EQ(r.activeVoxelCount(), v.activeVoxelCount());
    for (const glm::ivec3& c : {glm::ivec3(0, 0, 0), glm::ivec3(3, 4, 5), glm::ivec3(7, 7, 7)}) {
        ASSERT_TRUE(r.occupied(c));
        EXPECT_EQ(r.albedo(c), v.albedo(c));
        EXPECT_EQ(r.normal(c), v.normal(c));
        EXPECT_EQ(r.blockerSH(c), v.blockerSH(c));
    }
}
