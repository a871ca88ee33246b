// Bad mesh files through the CLI: a PLY face index out of range, a truncated PLY, a mesh whose
// triangles are all degenerate or hold NaN vertices, and coordinates near float's limit are each
// one line naming the file, exit 2 and no output, never a crash inside assimp or Embree. A mesh
// with only some NaN vertices renders from the rest.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "support/test_support.h"

using namespace voxgi::test;

namespace {
struct Case {
    const char* name;
    std::string content;
    const char* expected;  // part of the one-line message
};
}  // namespace

TEST(MeshFiles, MalformedFilesAreErrorsNotCrashes) {
    const std::string dir = makeTempDir("mesh-files");
    const std::string plyHeader =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n";
    std::vector<Case> cases = {
        {"index.ply", plyHeader + "3 0 1 7\n", "out of range"},
        {"degenerate.obj", "v 1 1 1\nv 1 1 1\nv 1 1 1\nf 1 2 3\n", "no triangle with finite vertices"},
        {"nan.obj", "v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "no triangle with finite vertices"},
        {"huge.obj", "v 3e38 0 0\nv 0 3e38 0\nv 0 0 3e38\nf 1 2 3\n", "coordinates reach"},
        // A header claiming 2e9 vertices (assimp would ask for 24 GB), one with a mangled keyword
        // (assimp loops on it for seconds; found by tests/fuzz/fuzz_mesh), a face of 0 indices.
        {"counts.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 2000000000\nproperty float x\n"
                       "property float y\nproperty float z\nend_header\n" + std::string(4096, '\0'),
         "PLY header declares elements of at least 24000000000 bytes"},
        {"keyword.ply", "ply\nformat ascii 1.0\nelement vertex 3\npro\x01\x00rty float x\nend_header\n0\n0\n0\n",
         "PLY header line 4: unknown keyword 'pro?"},
        {"empty-face.ply", plyHeader + "0\n", "face 0 has 0 indices"},
        // Starts like a PLY but its first line is not "ply" (assimp loops; tests/fuzz/fuzz_mesh).
        {"magic.obj", "plyoat x\nformat ascii 1.0\nelement vertex 3\nproperty float x\nend_header\n", "PLY header line 1"},
    };
    // The first 2000 bytes of a binary PLY: its faces end in the middle.
    const std::string bunny = sharedScenesDir().empty() ? "" : sharedScenesDir() + "/stanford-bunny/bun_zipper.ply";
    if (!bunny.empty() && fileExists(bunny)) {
        std::ifstream in(bunny, std::ios::binary);
        std::string head(2000, '\0');
        in.read(head.data(), 2000);
        cases.push_back({"truncated.ply", head, "PLY header declares elements of at least"});
    }
    for (const Case& c : cases) {
        const std::string path = dir + "/" + c.name;
        writeFile(path, c.content);
        for (const std::string& verb : {std::string("voxelize ") + path + " --voxel-size 0.05 -o " + dir + "/out.vdb",
                                        std::string("render ") + path + " --width 16 --height 16 -o " + dir + "/out.exr",
                                        std::string("reference ") + path + " --spp 1 --width 16 --height 16 -o " + dir + "/out.exr"}) {
            RunResult r = runVoxgi(verb);
            EXPECT_EQ(r.exitCode, 2) << verb << "\n" << r.output;
            EXPECT_NE(r.output.find(c.name), std::string::npos) << r.output;
            EXPECT_NE(r.output.find(c.expected), std::string::npos) << r.output;
            EXPECT_FALSE(fileExists(dir + "/out.vdb") || fileExists(dir + "/out.exr")) << verb;
        }
    }
}

TEST(MeshFiles, SomeNanVerticesLeaveTheRestRenderable) {
    const std::string dir = makeTempDir("mesh-partial-nan");
    writeFile(dir + "/partial.obj", "v nan 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 2 3 4\n");
    RunResult r = runVoxgi("reference " + dir + "/partial.obj --spp 2 --width 16 --height 16 -o " + dir + "/r.exr");
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("dropped NaN/Inf samples: 0"), std::string::npos) << r.output;
}

TEST(SceneFiles, AReferenceThatOverflowsFloatIsRefused) {
    // Every surface emitting 2.5e38: samples overflow float (and the image would be black with
    // every sample dropped), or their sums do.
    const std::string dir = makeTempDir("overflow");
    writeFile(dir + "/bright.json", R"({"camera": {"eye": [0, 0, 0], "target": [0, 0, 1], "resolution": [8, 8]},
        "materials": {"m": {"albedo": 0.8, "emission": 2.5e38}},
        "meshes": [{"type": "box", "material": "m", "inward": true, "transform": {"scale": 4}}]})");
    RunResult r = runVoxgi("reference " + dir + "/bright.json --spp 2 -o " + dir + "/r.exr");
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("overflow float"), std::string::npos) << r.output;
    EXPECT_FALSE(fileExists(dir + "/r.exr"));
}
