// Bad mesh files through the CLI: a PLY face index out of range, a truncated PLY, a mesh whose
// triangles are all degenerate or hold NaN vertices, and coordinates near float's limit are each
// one line naming the file, exit 2 and no output, never a crash inside assimp or Embree. A mesh
// with only some NaN vertices renders from the rest.
#include <gtest/gtest.h>

#include <cstdint>
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
         "PLY header line 4: control or non-ASCII byte 1"},
        {"empty-face.ply", plyHeader + "0\n", "face 0 has 0 indices"},
        // Found by tests/fuzz/fuzz_mesh. A .gltf that is not glTF: assimp would guess another reader
        // from its content (PLY, OpenGEX), which loops or reads past its buffer.
        {"magic.gltf", "plyoat x\nformat ascii 1.0\nelement vertex 3\nproperty float x\nend_header\n",
         "not a .gltf file that assimp recognises"},
        {"mesh.xyz", "v 0 0 0\n", "unknown mesh format '.xyz'"},
        // List counts assimp would reserve as they stand: an ASCII count beyond its uchar, and a
        // binary count of 2e9 in a 60-byte file.
        {"count.ply", plyHeader + "3333333333333333333 0 1 2\n",
         "PLY element 'face' item 0: list count '3333333333333333333' is not an integer its type holds"},
        {"binary-count.ply", "ply\nformat binary_little_endian 1.0\nelement face 1\nproperty list int int v\nend_header\n" +
                                 std::string("\x00\x94\x35\x77", 4) + std::string(12, '\0'),
         "PLY element 'face' item 0: list count 2000000000 runs past the end of the file"},
        // Header lines assimp misreads: a count glued to the next word, text after end_header.
        {"glued.ply", "ply\nformat ascii 1.0\nelement vertex 3property float x\nend_header\n0\n0\n0\n",
         "PLY header line 3: expected 'element NAME COUNT'"},
        {"after-end.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header 0 0\n0\n",
         "PLY header line 5: expected 'end_header' alone"},
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

// The checks that refuse the files above accept well-formed ones in each encoding.
TEST(MeshFiles, WellFormedPlyAndGltfLoad) {
    const std::string dir = makeTempDir("mesh-good");
    const std::string header = "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                               "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
    const float xyz[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const std::int32_t face[3] = {0, 1, 2};
    std::string binary = "ply\nformat binary_little_endian 1.0\ncomment one triangle\n" + header;
    binary.append(reinterpret_cast<const char*>(xyz), sizeof xyz);
    binary.push_back('\3');
    binary.append(reinterpret_cast<const char*>(face), sizeof face);
    writeFile(dir + "/binary.ply", binary);
    writeFile(dir + "/ascii.ply", "ply\r\nformat ascii 1.0\r\n" + header + "0 0 0\r\n1 0 0\n\n0 1 0\n3 0 1 2 \n");
    // One triangle in glTF 2.0, its buffer inline: 9 floats of positions, 3 uint16 indices.
    writeFile(dir + "/triangle.gltf", R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}], "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "buffers": [{"byteLength": 44, "uri": "data:application/octet-stream;base64,)"
                                           R"(AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAABAAIAAAA="}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
                      {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}]})");
    for (const char* name : {"binary.ply", "ascii.ply", "triangle.gltf"}) {
        RunResult r = runVoxgi(std::string("voxelize ") + dir + "/" + name + " --voxel-size 0.1 -o " + dir + "/out.vdb");
        EXPECT_EQ(r.exitCode, 0) << name << "\n" << r.output;
        EXPECT_NE(r.output.find("1 triangles"), std::string::npos) << name << "\n" << r.output;
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
