// Geometry volumes on disk: round trip, a real OpenVDB client (vdb_print) reading voxgi's
// files, the cache, and the voxelize / inspect verbs including their bad-input paths.
#include <cstdio>
#include <filesystem>
#include <cstring>
#include <fstream>
#include <iterator>

#include <gtest/gtest.h>

#include "scenes/errors.h"
#include "support/test_support.h"
#include "volumes/geometry_volume.h"

using namespace voxgi;
namespace fs = std::filesystem;

namespace {


void expectSameVolume(const SparseGeometryVolume& a, const SparseGeometryVolume& b) {
    ASSERT_EQ(a.levelCount(), b.levelCount());
    EXPECT_EQ(a.sourceHash(), b.sourceHash());
    EXPECT_EQ(a.hasSdf(), b.hasSdf());
    for (int l = 0; l < a.levelCount(); ++l) {
        EXPECT_FLOAT_EQ(a.voxelSize(l), b.voxelSize(l));
        ASSERT_EQ(a.activeVoxelCount(l), b.activeVoxelCount(l));
        for (const glm::ivec3& c : test::occupiedVoxels(a, l)) {
            ASSERT_TRUE(b.occupied(c, l));
            EXPECT_EQ(a.blockerSH(c, l), b.blockerSH(c, l));
            EXPECT_EQ(a.albedo(c, l), b.albedo(c, l));
            EXPECT_EQ(a.normal(c, l), b.normal(c, l));
        }
    }
}

std::string runProgram(const std::string& command, int& status) {
    std::string output;
    FILE* pipe = popen((command + " 2>&1").c_str(), "r");
    if (!pipe) {
        status = -1;
        return output;
    }
    char buffer[4096];
    while (std::size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) output.append(buffer, n);
    status = pclose(pipe);
    return output;
}

int lineCount(const std::string& s) {
    int n = 0;
    for (char c : s) n += c == '\n';
    return n;
}

VoxelizeSettings cornellSettings() {
    VoxelizeSettings s;
    s.voxelSize = 0.04f;
    s.levels = 2;
    return s;
}

}  // namespace

TEST(VolumeIo, WriteReadRoundTripAndNoTemporaryLeft) {
    std::string dir = test::makeTempDir("vol-io");
    VoxelizeSettings settings = cornellSettings();
    settings.sdf = true;
    SparseGeometryVolume v = voxelizeScene(test::cornellBox(), settings);
    writeGeometryVolume(dir + "/cornell.vdb", v);
    SparseGeometryVolume r = readGeometryVolume(dir + "/cornell.vdb");
    expectSameVolume(v, r);
    EXPECT_EQ(r.sdf({3, 3, 3}), v.sdf({3, 3, 3}));
    int files = 0;
    for (const auto& entry : fs::directory_iterator(dir)) files += entry.is_regular_file();
    EXPECT_EQ(files, 1);
}

TEST(VolumeIo, VdbPrintReadsTheGridsBack) {
    const std::string program = VDB_PRINT_PROGRAM;
    ASSERT_FALSE(program.empty()) << "VDB_PRINT_PROGRAM is not configured";
    ASSERT_TRUE(fs::exists(program)) << program;
    std::string dir = test::makeTempDir("vol-vdbprint");
    VoxelizeSettings settings = cornellSettings();
    settings.sdf = true;
    SparseGeometryVolume v = voxelizeScene(test::cornellBox(), settings);
    writeGeometryVolume(dir + "/cornell.vdb", v);
    int status = 0;
    std::string out = runProgram(program + " -l -m " + dir + "/cornell.vdb", status);
    EXPECT_EQ(status, 0) << out;
    for (const char* grid : {"occupancy", "albedo", "normal", "blocker_sh0", "blocker_sh1", "blocker_sh2",
                             "blocker_sh3", "occupancy_L1", "albedo_L1", "normal_L1", "blocker_sh3_L1", "sdf"})
        EXPECT_NE(out.find(std::string("Name: ") + grid + "\n"), std::string::npos) << grid << "\n" << out;
    EXPECT_NE(out.find("voxgi_source_hash: " + v.sourceHash()), std::string::npos) << out;
    EXPECT_NE(out.find("voxgi_sh_convention"), std::string::npos);
    EXPECT_NE(out.find("class: level set"), std::string::npos);
    EXPECT_NE(out.find("file_voxel_count: " + std::to_string(v.activeVoxelCount(0)) + "\n"), std::string::npos) << out;
}

TEST(VolumeIo, CacheReusesMatchingFilesAndRebuildsOtherwise) {
    std::string dir = test::makeTempDir("vol-cache") + "/cache";
    Scene scene = test::cornellBox();
    VoxelizeSettings settings = cornellSettings();
    bool cached = true;
    SparseGeometryVolume first = loadOrBuildGeometryVolume(scene, settings, dir, &cached);
    EXPECT_FALSE(cached);
    std::string path = dir + "/geometry-" + first.sourceHash() + ".vdb";
    ASSERT_TRUE(fs::exists(path));
    SparseGeometryVolume second = loadOrBuildGeometryVolume(scene, settings, dir, &cached);
    EXPECT_TRUE(cached);
    expectSameVolume(first, second);

    VoxelizeSettings finer = settings;
    finer.voxelSize = 0.03f;
    SparseGeometryVolume other = loadOrBuildGeometryVolume(scene, finer, dir, &cached);
    EXPECT_FALSE(cached);
    EXPECT_NE(other.sourceHash(), first.sourceHash());

    Scene moved = scene;
    moved.meshes[0].positions[0].x += 0.01f;
    EXPECT_NE(geometryHash(moved, settings), geometryHash(scene, settings));
    Scene recoloured = scene;
    recoloured.materials[0].albedo.x *= 0.5f;
    EXPECT_NE(geometryHash(recoloured, settings), geometryHash(scene, settings));
    // The albedo grid holds the diffuse albedo, which metallic and specular change too.
    Scene metal = scene;
    metal.materials[0].metallic = 0.5f;
    EXPECT_NE(geometryHash(metal, settings), geometryHash(scene, settings));
    Scene coated = scene;
    coated.materials[0].specular = 0.04f;
    EXPECT_NE(geometryHash(coated, settings), geometryHash(scene, settings));

    // A damaged cache entry is rebuilt, not trusted and not fatal.
    test::writeFile(path, "not a vdb file");
    SparseGeometryVolume rebuilt = loadOrBuildGeometryVolume(scene, settings, dir, &cached);
    EXPECT_FALSE(cached);
    expectSameVolume(first, rebuilt);
    loadOrBuildGeometryVolume(scene, settings, dir, &cached);
    EXPECT_TRUE(cached);
}

TEST(VolumeIo, BadFilesAreInputErrorsNamingTheFile) {
    std::string dir = test::makeTempDir("vol-bad");
    SparseGeometryVolume v = voxelizeScene(test::cornellBox(), cornellSettings());
    writeGeometryVolume(dir + "/good.vdb", v);
    auto size = fs::file_size(dir + "/good.vdb");
    fs::copy_file(dir + "/good.vdb", dir + "/truncated.vdb");
    fs::resize_file(dir + "/truncated.vdb", size / 2);
    test::writeFile(dir + "/garbage.vdb", std::string(4096, 'x'));
    test::writeFile(dir + "/empty.vdb", "");
    // The first 100 bytes (OpenVDB alone asked for 4 GB and took 8 s on it), a flipped bit in
    // the file's UUID (read as "0 grids" before), and a descriptor whose grid ends past the file.
    fs::copy_file(dir + "/good.vdb", dir + "/head100.vdb");
    fs::resize_file(dir + "/head100.vdb", 100);
    std::string bytes;
    {
        std::ifstream in(dir + "/good.vdb", std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(in), {});
    }
    std::string uuid = bytes;
    uuid[40] ^= 0x10;
    test::writeFile(dir + "/uuid.vdb", uuid);
    test::writeFile(dir + "/cut-grid.vdb", bytes.substr(0, 2000) + std::string(5000, '\0'));
    for (const char* name : {"/absent.vdb", "/truncated.vdb", "/garbage.vdb", "/empty.vdb", "/head100.vdb", "/uuid.vdb",
                             "/cut-grid.vdb"}) {
        try {
            readGeometryVolume(dir + name);
            ADD_FAILURE() << name << " was accepted";
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find(dir + name), std::string::npos) << e.what();
        }
    }
    // inspect read the flipped-UUID file as "0 grid(s)" and exited 0.
    auto r = test::runVoxgi("inspect " + dir + "/uuid.vdb");
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("corrupt file UUID"), std::string::npos) << r.output;
}

// Corruptions inside a grid's head that made OpenVDB read for seconds and gigabytes (found by
// tests/fuzz/fuzz_vdb): a metadata value whose size disagrees with its type (OpenVDB reads
// the type's size and every later length comes from the middle of a value: 10 GB), a root node
// claiming 2e9 tiles (a 14 s loop reading nothing), and a pre-2013 file version.
TEST(VolumeIo, CorruptGridHeadsAreRefusedBeforeOpenVdbReadsThem) {
    std::string dir = test::makeTempDir("vol-grid-head");
    writeGeometryVolume(dir + "/good.vdb", voxelizeScene(test::cornellBox(), cornellSettings()));
    std::string bytes;
    {
        std::ifstream in(dir + "/good.vdb", std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(in), {});
    }
    auto replaced = [&](const std::string& from, const std::string& to) {
        std::string copy = bytes;
        const std::size_t at = copy.find(from);
        EXPECT_NE(at, std::string::npos) << from;
        if (at != std::string::npos) copy.replace(at, from.size(), to);
        return copy;
    };
    // The first grid's "file_bbox_max" is a vec3i of 12 bytes; as a mat4d OpenVDB reads 128.
    test::writeFile(dir + "/metadata.vdb", replaced("vec3i", "mat4d"));
    // After the first transform's type name and its 144 bytes: the tree's buffer count, its
    // background value (the first grid is a bool occupancy tree: 1 byte), then the tile count.
    const std::string map = "UniformScaleTranslateMap";
    std::string tiles = bytes;
    const std::size_t tileCount = tiles.find(map) + map.size() + 144 + 4 + 1;
    ASSERT_LT(tileCount + 4, tiles.size());
    const std::uint32_t many = 2000000000u;
    std::memcpy(&tiles[tileCount], &many, 4);
    test::writeFile(dir + "/tiles.vdb", tiles);
    std::string old = bytes;
    old[8] = char(200);
    test::writeFile(dir + "/version.vdb", old);
    for (const auto& [name, expected] : {std::pair<std::string, std::string>{"metadata.vdb", "of type mat4d has 12 bytes, not 128"},
                                         {"tiles.vdb", "root node of 2000000000 tiles"},
                                         {"version.vdb", "file format version 200 predates"}}) {
        auto r = test::runVoxgi("inspect " + dir + "/" + name);
        EXPECT_EQ(r.exitCode, 2) << name << "\n" << r.output;
        EXPECT_NE(r.output.find(dir + "/" + name), std::string::npos) << r.output;
        EXPECT_NE(r.output.find(expected), std::string::npos) << r.output;
    }
}

TEST(VoxelizeCli, WritesTheGridSetAndInspectDescribesIt) {
    std::string dir = test::makeTempDir("vol-cli");
    auto r = test::runVoxgi("voxelize cornell-box --voxel-size 0.04 --levels 2 -o " + dir + "/cb.vdb");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("level 1: voxel 0.08"), std::string::npos) << r.output;
    SparseGeometryVolume v = readGeometryVolume(dir + "/cb.vdb");
    EXPECT_EQ(v.levelCount(), 2);
    EXPECT_GT(v.activeVoxelCount(0), 1000u);

    auto i = test::runVoxgi("inspect " + dir + "/cb.vdb");
    ASSERT_EQ(i.exitCode, 0) << i.output;
    for (const std::string& text : std::vector<std::string>{"occupancy ", "occupancy_L1", "blocker_sh2_L1", "vec3s", "bool", "fog volume",
                             "active " + std::to_string(v.activeVoxelCount(0)), "index [", "world [", "memory"})
        EXPECT_NE(i.output.find(text), std::string::npos) << text << "\n" << i.output;

    auto s = test::runVoxgi("inspect " + dir + "/cb.vdb --stats --bins 5");
    ASSERT_EQ(s.exitCode, 0) << s.output;
    EXPECT_NE(s.output.find("blocker_sh0 (value"), std::string::npos) << s.output;
    EXPECT_NE(s.output.find("normal (length"), std::string::npos) << s.output;

    auto p = test::runVoxgi("inspect " + dir + "/cb.vdb --slice z=0.25 -o " + dir + "/slice.png --grid albedo");
    ASSERT_EQ(p.exitCode, 0) << p.output;
    ASSERT_TRUE(test::fileExists(dir + "/slice.png"));
    EXPECT_GT(fs::file_size(dir + "/slice.png"), 50u);
    EXPECT_EQ(test::runVoxgi("inspect " + dir + "/cb.vdb --slice w=1 -o " + dir + "/s2.png").exitCode, 2);
    EXPECT_EQ(test::runVoxgi("inspect " + dir + "/cb.vdb --slice z=0.2 -o " + dir + "/s3.png --grid nope").exitCode, 2);
    // A plane outside the grid's active voxels (or beyond int once in index space) is refused.
    for (const char* far : {"z=1e300", "z=-5"}) {
        auto r = test::runVoxgi("inspect " + dir + "/cb.vdb --slice " + far + " -o " + dir + "/s4.png --grid albedo");
        EXPECT_EQ(r.exitCode, 2) << r.output;
        EXPECT_NE(r.output.find("outside grid 'albedo'"), std::string::npos) << r.output;
        EXPECT_FALSE(test::fileExists(dir + "/s4.png"));
    }
    EXPECT_FALSE(test::fileExists(dir + "/s3.png"));
}

TEST(VoxelizeCli, BadInputExitsTwoWithOneLineAndNoOutput) {
    std::string dir = test::makeTempDir("vol-cli-bad");
    test::writeFile(dir + "/garbage.vdb", "garbage");
    for (const std::string& file : {dir + "/garbage.vdb", dir + "/absent.vdb"}) {
        auto r = test::runVoxgi("inspect " + file);
        EXPECT_EQ(r.exitCode, 2) << r.output;
        EXPECT_EQ(lineCount(r.output), 1) << r.output;
        EXPECT_NE(r.output.find(file), std::string::npos) << r.output;
    }
    auto absurd = test::runVoxgi("voxelize cornell-box --voxel-size 1e-4 -o " + dir + "/huge.vdb");
    EXPECT_EQ(absurd.exitCode, 2) << absurd.output;
    EXPECT_EQ(lineCount(absurd.output), 1) << absurd.output;
    EXPECT_NE(absurd.output.find("--max-voxels"), std::string::npos) << absurd.output;
    EXPECT_FALSE(test::fileExists(dir + "/huge.vdb"));
    auto capped = test::runVoxgi("voxelize cornell-box --voxel-size 0.01 --max-voxels 1000 -o " + dir + "/capped.vdb");
    EXPECT_EQ(capped.exitCode, 2) << capped.output;
    EXPECT_FALSE(test::fileExists(dir + "/capped.vdb"));
    EXPECT_EQ(test::runVoxgi("voxelize cornell-box --voxel-size -1 -o " + dir + "/neg.vdb").exitCode, 2);
    EXPECT_EQ(test::runVoxgi("voxelize cornell-box --voxel-size 1e-9 -o " + dir + "/tiny.vdb").exitCode, 2);
    EXPECT_EQ(test::runVoxgi("voxelize cornell-box -o " + dir + "/nosize.vdb").exitCode, 2);
    // A mesh whose every triangle has zero area.
    test::writeFile(dir + "/degenerate.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 0 1\nv 0 0 3\nf 1 2 3\nf 1 4 5\n");
    auto degenerate = test::runVoxgi("voxelize " + dir + "/degenerate.obj --voxel-size 0.1 -o " + dir + "/d.vdb");
    EXPECT_EQ(degenerate.exitCode, 2) << degenerate.output;
    EXPECT_EQ(lineCount(degenerate.output), 1) << degenerate.output;
    EXPECT_FALSE(test::fileExists(dir + "/d.vdb"));
}
