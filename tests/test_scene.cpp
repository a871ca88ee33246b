// Scene model: parsing of good files, each kind of bad file, mesh import (OBJ+MTL, glTF).
#include <gtest/gtest.h>

#include <cmath>

#include "scenes/errors.h"
#include "scenes/mesh_import.h"
#include "scenes/scene_loader.h"
#include "shaders/shared/constants.h"
#include "support/test_support.h"

using namespace voxgi;

namespace {

std::string minimal(const std::string& extra) {
    return R"({"camera": {"eye": [0, 0, 3], "target": [0, 0, 0]},
               "materials": {"white": {"albedo": 0.5}})" + extra + "}";
}

std::string errorOf(const std::string& json) {
    try {
        parseSceneJson(json, "bad.json");
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(Scene, BuiltinCornellBoxHasPublishedDimensions) {
    Scene s = test::cornellBox();
    Bounds b = s.bounds();
    EXPECT_NEAR(b.min.x, 0.0f, 1e-6f);
    EXPECT_NEAR(b.max.x, 0.556f, 1e-6f);
    EXPECT_NEAR(b.max.y, 0.5488f, 1e-6f);
    EXPECT_NEAR(b.max.z, 0.5592f, 1e-6f);
    ASSERT_EQ(s.lights.size(), 1u);
    EXPECT_EQ(s.lights[0].type, LightType::Quad);
    EXPECT_NEAR(s.lights[0].area(), 0.130f * 0.105f, 1e-7f);
    EXPECT_NEAR(s.lights[0].quadNormal().y, -1.0f, 1e-6f);  // emits downwards
    EXPECT_LT(s.lights[0].position.y, 0.5488f);              // under the ceiling
    // 5 walls + 2 blocks of 5 quads = 15 quads, plus the light quad: 32 triangles.
    EXPECT_EQ(s.triangleCount(), 32u);
    EXPECT_NEAR(s.camera.fovYDegrees, 2.0 * std::atan(12.5 / 35.0) * 180.0 / shading::kPiDouble, 1e-3);
    EXPECT_EQ(s.gi.getString("method", ""), "clpv");
}

TEST(Scene, ParsesEveryLightKindAndPrimitive) {
    Scene s = parseSceneJson(minimal(R"(,
        "sky": {"radiance": [0.1, 0.2, 0.3]},
        "lights": [
          {"type": "point", "position": [0, 1, 0], "intensity": 5},
          {"type": "spot", "position": [0, 2, 0], "direction": [0, -1, 0], "intensity": [1, 2, 3],
           "inner_angle": 10, "outer_angle": 20},
          {"type": "directional", "direction": [0, -2, 0], "irradiance": 3, "angular_diameter": 0.53},
          {"type": "quad", "corner": [0, 1, 0], "edge_u": [1, 0, 0], "edge_v": [0, 0, 1], "radiance": 2}],
        "meshes": [
          {"type": "box", "material": "white", "transform": {"translate": [1, 0, 0], "scale": 2}},
          {"type": "sphere", "material": "white", "segments": 8},
          {"type": "quad", "material": "white", "corners": [[0,0,0],[1,0,0],[1,0,1],[0,0,1]]},
          {"type": "polygons", "material": "white", "vertices": [[0,0,0],[1,0,0],[0,1,0]], "faces": [[0,1,2]]}],
        "gi": {"method": "direct", "lpv": {"steps": 16, "glossy": true}})"),
                             "good.json");
    ASSERT_EQ(s.lights.size(), 4u);
    EXPECT_EQ(s.lights[1].emission, glm::vec3(1, 2, 3));
    EXPECT_NEAR(glm::length(s.lights[2].direction), 1.0f, 1e-6f);  // normalized
    EXPECT_FLOAT_EQ(s.lights[2].angularDiameterDegrees, 0.53f);
    EXPECT_TRUE(s.sky.enabled);
    // box 12 + sphere + quad 2 + triangle 1 + the quad light's own geometry 2
    EXPECT_EQ(s.meshes.size(), 5u);
    EXPECT_EQ(s.meshes[0].triangleCount(), 12u);
    EXPECT_NEAR(s.meshes[0].positions[0].x, 1.0f + 1.0f, 1e-5f);  // scale 2 then translate 1 (|x| = 1)
    EXPECT_EQ(s.gi.getString("lpv.steps", ""), "16");
    EXPECT_EQ(s.gi.getString("lpv.glossy", ""), "true");
    EXPECT_TRUE(s.materials.back().isEmissive());
}

TEST(Scene, MalformedJsonNamesLine) {
    std::string e = errorOf("{\n  \"camera\": {\n    \"eye\": [0, 0, 1,]\n  }\n}");
    EXPECT_NE(e.find("bad.json: line 3"), std::string::npos) << e;
    EXPECT_NE(e.find("malformed JSON"), std::string::npos) << e;
}

TEST(Scene, NumbersBeyondTheirTypeAreErrorsNotWrappedValues) {
    // 1e999 overflows double inside the JSON library; a resolution past int would wrap to 64.
    EXPECT_NE(errorOf(R"({"camera": {"eye": [0, 0, 1e999], "target": [0, 0, 0]}})").find("bad.json: malformed JSON"),
              std::string::npos);
    const std::string wrapped = errorOf(R"({"camera": {"eye": [0, 0, 3], "target": [0, 0, 0], "resolution": [4294967360, 64]}})");
    EXPECT_NE(wrapped.find("/camera/resolution/0: integer out of range"), std::string::npos) << wrapped;
}

TEST(Scene, UnknownFieldIsNamed) {
    std::string e = errorOf(minimal(R"(, "lights": [{"type": "point", "position": [0,0,0], "intensty": 1}])"));
    EXPECT_NE(e.find("/lights/0/intensty"), std::string::npos) << e;
    EXPECT_NE(e.find("unknown field"), std::string::npos) << e;
    e = errorOf(minimal(R"(, "camrea": {})"));
    EXPECT_NE(e.find("/camrea"), std::string::npos) << e;
}

TEST(Scene, WrongTypesAreNamed) {
    EXPECT_NE(errorOf(minimal(R"(, "lights": [{"type": "point", "position": "up"}])")).find("/lights/0/position: expected [x, y, z]"),
              std::string::npos);
    EXPECT_NE(errorOf(R"({"camera": {"eye": [0,0,1], "target": [0,0,0], "fov": "wide"}})").find("/camera/fov: expected a number"),
              std::string::npos);
    EXPECT_NE(errorOf(minimal(R"(, "meshes": [{"type": "box", "material": "gold"}])")).find("unknown material 'gold'"),
              std::string::npos);
    EXPECT_NE(errorOf(minimal(R"(, "lights": [{"type": "laser"}])")).find("/lights/0/type"), std::string::npos);
    EXPECT_NE(errorOf(minimal(R"(, "lights": [{"type": "directional", "direction": [0, -1, 0], "angular_diameter": 30}])"))
                  .find("/lights/0/angular_diameter"),
              std::string::npos);
    EXPECT_NE(errorOf(R"({"camera": {"eye": [0,0,0], "target": [0,0,0]}})").find("must differ from eye"),
              std::string::npos);
    EXPECT_NE(errorOf(R"({"materials": {}})").find("missing field 'camera'"), std::string::npos);
    EXPECT_NE(errorOf(minimal(R"(, "gi": {"lpv": {"steps": [1]}})")).find("/gi/lpv/steps"), std::string::npos);
    EXPECT_NE(errorOf(R"({"camera": {"eye": [0,0,1], "target": [0,0,0]}, "materials": {"m": {"albedo": 1.5}}})")
                  .find("/materials/m/albedo"),
              std::string::npos);
}

TEST(Scene, MissingFilesAreNamed) {
    EXPECT_THROW(loadSceneFile("/nonexistent/scene.json"), InputError);
    std::string e = errorOf(minimal(R"(, "meshes": [{"type": "file", "path": "missing.obj"}])"));
    EXPECT_NE(e.find("/meshes/0/path"), std::string::npos) << e;
    EXPECT_NE(e.find("missing.obj"), std::string::npos) << e;
}

TEST(Scene, GiSettingsOverridesAndUnknownKeys) {
    GiSettings gi;
    gi.applyOverride("lpv.steps=32");
    EXPECT_EQ(gi.getString("lpv.steps", "16"), "32");
    EXPECT_THROW(gi.applyOverride("steps32"), InputError);
    gi.set("lpv.stpes", "3");
    EXPECT_THROW(gi.requireKnown("lpv", {"steps"}), InputError);
}

TEST(MeshImport, ObjWithMtlAndTexture) {
    std::string dir = test::makeTempDir("obj");
    // A 2x2 PNG written by hand would need an encoder; use a PPM texture instead (stb reads it).
    test::writeFile(dir + "/tex.ppm", std::string("P6\n2 2\n255\n") + std::string("\xff\x00\x00\x00\xff\x00\x00\x00\xff\xff\xff\xff", 12));
    test::writeFile(dir + "/m.mtl", "newmtl red\nKd 0.8 0.1 0.1\nmap_Kd tex.ppm\n");
    test::writeFile(dir + "/m.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                                    "usemtl red\nf 1/1 2/2 3/3 4/4\n");
    Scene s;
    MeshImportStats st = importMeshFile(dir + "/m.obj", glm::mat4(1.0f), s);
    EXPECT_EQ(st.triangles, 2u);  // the quad is triangulated
    EXPECT_EQ(st.textures, 1u);
    ASSERT_FALSE(s.materials.empty());
    const Material& m = s.materials[s.meshes[0].materialIds[0]];
    EXPECT_NEAR(m.albedo.x, 0.8f, 1e-6f);
    ASSERT_GE(m.albedoTexture, 0);
    EXPECT_EQ(s.textures[std::size_t(m.albedoTexture)].width, 2);
    // Mean of red, green, blue and white texels: 0.5 in every channel.
    EXPECT_NEAR(s.textures[std::size_t(m.albedoTexture)].averageLinear.x, 0.5f, 1e-3f);
}

// A scene may change some fields of a mesh file's material by name (a polished floor, glass in
// the windows), and names a material the file lacks in a one-line error.
TEST(MeshImport, MaterialSettingsChangeTheFilesMaterialByName) {
    std::string dir = test::makeTempDir("obj-settings");
    test::writeFile(dir + "/m.mtl", "newmtl floor\nKd 0.5 0.4 0.3\nnewmtl wall\nKd 0.7 0.7 0.7\n");
    test::writeFile(dir + "/m.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                                    "usemtl floor\nf 1 2 3\nusemtl wall\nf 1 3 4\n");
    auto scene = [&](const std::string& settings) {
        test::writeFile(dir + "/s.json", R"({"camera": {"eye": [0, 0, 3], "target": [0, 0, 0]},
            "meshes": [{"type": "file", "path": "m.obj", "material_settings": )" + settings + "}]}");
        return loadSceneFile(dir + "/s.json");
    };
    const Scene s = scene(R"({"floor": {"roughness": 0, "specular": 0.05}})");
    int changed = 0;
    for (const Material& m : s.materials) {
        if (m.name == "floor") {
            ++changed;
            EXPECT_EQ(m.roughness, 0.0f);
            EXPECT_EQ(m.specular, 0.05f);
            EXPECT_NEAR(m.albedo.x, 0.5f, 1e-6f);  // the file's own fields stay
        } else {
            EXPECT_EQ(m.specular, 0.0f) << m.name;
        }
    }
    EXPECT_EQ(changed, 1);
    try {
        scene(R"({"marble": {"roughness": 0}})");
        ADD_FAILURE() << "an unknown material was accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("material_settings/marble"), std::string::npos) << e.what();
    }
    EXPECT_THROW(scene(R"({"floor": {"roughness": 2}})"), InputError);
}

TEST(MeshImport, Gltf2EmbeddedBuffer) {
    std::string dir = test::makeTempDir("gltf");
    // One triangle: 3 float3 positions (36 bytes) + 3 uint16 indices (6 bytes, padded to 8).
    const char* buffer =
        "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAABAAIAAAA=";
    std::string gltf = std::string(R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
      "nodes": [{"mesh": 0, "translation": [0, 0, -2]}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]}],
      "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.4, 0.6, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.5}}],
      "buffers": [{"byteLength": 44, "uri": "data:application/octet-stream;base64,)") + buffer + R"("}],
      "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
      "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0,0,0], "max": [1,1,0]},
                    {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}]})";
    test::writeFile(dir + "/tri.gltf", gltf);
    Scene s;
    MeshImportStats st = importMeshFile(dir + "/tri.gltf", glm::mat4(1.0f), s);
    EXPECT_EQ(st.triangles, 1u);
    const Material& m = s.materials[s.meshes[0].materialIds[0]];
    EXPECT_NEAR(m.albedo.z, 0.6f, 1e-5f);
    EXPECT_NEAR(m.roughness, 0.5f, 1e-5f);
    EXPECT_NEAR(s.bounds().min.z, -2.0f, 1e-5f);  // the node transform is applied
}

TEST(MeshImport, BrokenMeshIsAnInputError) {
    std::string dir = test::makeTempDir("broken");
    test::writeFile(dir + "/broken.obj", "this is not an obj file\nf 1 2 3\n");
    Scene s;
    EXPECT_THROW(importMeshFile(dir + "/broken.obj", glm::mat4(1.0f), s), InputError);
    EXPECT_THROW(importMeshFile(dir + "/absent.obj", glm::mat4(1.0f), s), InputError);
}

TEST(MeshImport, SharedCornellObjLoadsWhenPresent) {
    std::string dir = test::sharedScenesDir();
    if (dir.empty()) GTEST_SKIP() << "../shared/scenes not present";
    Scene s;
    MeshImportStats st = importMeshFile(dir + "/cornell-box/CornellBox-Original.obj", glm::mat4(1.0f), s);
    EXPECT_EQ(st.triangles, 36u);
}
