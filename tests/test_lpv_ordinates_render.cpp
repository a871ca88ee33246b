// lpv.transport=ordinates through the frame renderer: the Cornell box's regions get the path
// tracer's indirect light (the SH transport's ceiling got 0.04-0.6 of it), a sunlit floor under an
// open sky gets none of its own light back, the gl back end's sweeps match the cpu's, and the
// .vdb dump.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "gi/lpv/lpv_desc.h"
#include "gi/metrics/regions.h"
#include "gi/pathtrace/path_tracer.h"
#include "render/frame/frame_renderer.h"
#include "scenes/errors.h"
#include "scenes/primitives.h"
#include "scenes/scene_loader.h"
#include "support/test_support.h"

using namespace voxgi;

namespace {

class LpvOrdinatesRender : public ::testing::Test {
protected:
    static void SetUpTestSuite() { test::useHeadlessContext(); }
};

Image render(const Scene& scene, const std::string& method) {
    FrameRenderer r(scene, FrameOptions{}, method);
    r.renderFrame();
    return r.resolve();
}

// The cpu and gl back ends' indirect layers: within 1e-4 of the largest value (float rounding).
void expectIndirectLayersAgree(const Image& cpu, const Image& gl, const std::string& method) {
    const ImageLayer* a = cpu.find("indirect");
    const ImageLayer* b = gl.find("indirect");
    ASSERT_TRUE(a && b) << method;
    double largest = 0.0, worst = 0.0;
    for (std::size_t i = 0; i < a->data.size(); ++i) {
        largest = std::max(largest, double(a->data[i]));
        worst = std::max(worst, std::abs(double(a->data[i]) - double(b->data[i])));
    }
    EXPECT_GT(largest, 0.0) << method;
    EXPECT_LE(worst, 1e-4 * largest) << method;
}

}  // namespace

// Measured at 48^2 against 512 spp: the regions with 40 pixels or more at 0.89-1.05 (docs/lpv.md
// has 128^2); the SH transport's ceiling is far below 0.8. clpv with camera-centred cascades
// reads the box from its coarse outer cascades (0.79-0.97 at 128^2), so it runs on the scene's bounds.
TEST_F(LpvOrdinatesRender, CornellBoxRegionsGetThePathTracersIndirectLight) {
    Scene s = test::cornellBox();
    s.camera.width = s.camera.height = 48;
    PathTracerOptions o;
    o.width = o.height = 48;
    PathTracer pt(s, o);
    pt.render(512);
    const Image reference = pt.image();
    s.gi.set("lpv.transport", "ordinates");
    // lpv, and clpv with its cascades on the scene's bounds (the camera stands outside the box).
    for (const char* method : {"lpv", "clpv"}) {
        SCOPED_TRACE(method);
        Scene m = s;
        if (std::string(method) == "clpv") m.gi.set("lpv.cascade_bounds", "scene");
        const Image test = render(m, method);
        int checked = 0;
        for (const RegionMean& r : regionMeans(test, reference, m, "indirect")) {
            if (r.pixels < 40) continue;  // the light's rim, the block top: too few pixels at 48^2
            EXPECT_GT(r.ratio, 0.8) << r.name;
            EXPECT_LT(r.ratio, 1.25) << r.name;
            ++checked;
        }
        EXPECT_GE(checked, 5);
    }
}

// A sunlit floor with nothing above it: its true indirect light is zero. The SH transport gave
// it 0.42 of its own radiance back (docs/lpv.md, "Self-illumination").
// lpv.cube_read reaches the apply pass: the Cornell box's walls, floor and ceiling face along the
// axes, where both reads give the face's own value, and its blocks are turned about y, where the
// quadratic read differs.
TEST_F(LpvOrdinatesRender, TheQuadraticCubeReadChangesOnlyTiltedReceivers) {
    Scene s = test::cornellBox();
    s.camera.width = s.camera.height = 48;
    const Image ambient = render(s, "lpv");
    s.gi.set("lpv.cube_read", "quadratic");
    const Image quadratic = render(s, "lpv");
    const ImageLayer* a = ambient.find("indirect");
    const ImageLayer* q = quadratic.find("indirect");
    const ImageLayer* normal = ambient.find("normal");
    ASSERT_TRUE(a && q && normal);
    int axisPixels = 0, tiltedPixels = 0, tiltedChanged = 0;
    for (std::size_t i = 0; i < a->data.size() / 3; ++i) {
        const glm::vec3 n(normal->data[3 * i], normal->data[3 * i + 1], normal->data[3 * i + 2]);
        const float largest = std::max({std::abs(n.x), std::abs(n.y), std::abs(n.z)});
        if (glm::length(n) < 0.5f) continue;  // no surface
        const float before = a->data[3 * i] + a->data[3 * i + 1] + a->data[3 * i + 2];
        const float after = q->data[3 * i] + q->data[3 * i + 1] + q->data[3 * i + 2];
        if (largest > 0.9999f) {
            ++axisPixels;
            EXPECT_NEAR(after, before, 1e-5f * std::max(before, 1e-3f)) << "pixel " << i;
        } else if (largest < 0.98f) {
            ++tiltedPixels;
            if (std::abs(after - before) > 0.01f * before) ++tiltedChanged;
        }
    }
    EXPECT_GT(axisPixels, 1000);
    EXPECT_GT(tiltedPixels, 50);
    EXPECT_GT(tiltedChanged, tiltedPixels / 2);
}

TEST_F(LpvOrdinatesRender, ASunlitFloorUnderAnOpenSkyGetsNoIndirectLight) {
    Scene s = parseSceneJson(R"({"camera": {"eye": [0, 6, 9], "target": [0, 0, 0], "resolution": [32, 32]},
        "materials": {"stone": {"albedo": 0.7}},
        "lights": [{"type": "directional", "direction": [0.3, -1, 0.2], "irradiance": 5}],
        "meshes": [{"type": "quad", "material": "stone", "corners": [[-10, 0, 10], [10, 0, 10], [10, 0, -10], [-10, 0, -10]]}],
        "gi": {"lpv": {"transport": "ordinates"}}})",
                             "floor.json");
    const Image img = render(s, "lpv");
    double direct = 0.0, indirect = 0.0;
    for (float v : img.find("direct")->data) direct += double(v);
    for (float v : img.find("indirect")->data) indirect += double(v);
    EXPECT_GT(direct, 0.0);
    EXPECT_EQ(indirect, 0.0);
}

// lpv.tap_visibility: a lamp 0.3 m before a thin wall on an open floor. The floor behind the
// wall reads cells whose centres lie on the lamp's side, in front of it, through the wall; the
// path tracer has almost no indirect light there (nothing behind the wall is lit). With the
// taps it cannot see dropped, the strip behind the wall comes within reach of the reference,
// and the lamp's side, which sees its taps, keeps its light.
TEST_F(LpvOrdinatesRender, TapVisibilityKeepsTheLightOfAWallsLitSideOffItsBack) {
    Scene s = parseSceneJson(R"({"camera": {"eye": [0.0, 3.0, 3.0], "target": [0.0, 0.0, -0.5], "resolution": [48, 48]},
        "materials": {"stone": {"albedo": 0.7}},
        "lights": [{"type": "point", "position": [-0.3, 0.5, 0.0], "intensity": 5}],
        "meshes": [{"type": "quad", "material": "stone", "corners": [[-4, 0, 4], [4, 0, 4], [4, 0, -4], [-4, 0, -4]]},
                   {"type": "box", "material": "stone", "transform": {"scale": [0.02, 1.0, 4.0], "translate": [0, 0.5, 0]}}],
        "regions": [{"name": "behind", "min": [0.02, -0.01, -1.5], "max": [0.5, 0.01, 1.5], "facing": [0, 1, 0]},
                    {"name": "lit_side", "min": [-0.8, -0.01, -1.5], "max": [-0.02, 0.01, 1.5], "facing": [0, 1, 0]}],
        "gi": {"lpv": {"resolution": 32}}})",
                             "wall.json");
    PathTracerOptions o;
    o.width = o.height = 48;
    PathTracer pt(s, o);
    pt.render(256);
    const Image reference = pt.image();
    const Image plain = render(s, "lpv");
    std::map<std::string, RegionMean> before;
    for (const RegionMean& r : regionMeans(plain, reference, s, "indirect")) before[r.name] = r;
    ASSERT_GT(before["behind"].pixels, 30u);
    ASSERT_GT(before["lit_side"].pixels, 30u);
    EXPECT_GT(before["behind"].ratio, 3.0);  // the leak
    // A ray per pixel and tap, and the masks traced once per cell and side (tap_masks.h).
    for (const char* taps : {"rays", "cells"}) {
        s.gi.set("lpv.tap_visibility", taps);
        const Image visible = render(s, "lpv");
        std::map<std::string, RegionMean> after;
        for (const RegionMean& r : regionMeans(visible, reference, s, "indirect")) after[r.name] = r;
        std::printf("%s: behind the wall %.3g -> %.3g of the reference's indirect; lamp's side %.3g -> %.3g\n", taps,
                    before["behind"].ratio, after["behind"].ratio, before["lit_side"].ratio, after["lit_side"].ratio);
        EXPECT_LT(after["behind"].ratio, 0.5 * before["behind"].ratio) << taps;
        EXPECT_NEAR(after["lit_side"].ratio, before["lit_side"].ratio, 0.1 * before["lit_side"].ratio) << taps;
    }
}

// The gl back end sweeps on the GPU: the same light as the cpu's, up to float rounding, for one
// volume and for cascades with their ring and inner light. Small balls in the air, each inside a
// cell or two, are surfaces whose normals cancel: they stop light by their shadow.
TEST_F(LpvOrdinatesRender, GlSweepsMatchTheCpuSweeps) {
    for (const std::string method : {"lpv", "clpv"}) {
        Scene s = test::cornellBox();
        for (const glm::vec3 at : {glm::vec3(0.12f, 0.40f, 0.10f), glm::vec3(0.42f, 0.33f, 0.40f), glm::vec3(0.20f, 0.25f, 0.45f)})
            s.meshes.push_back(makeSphere(glm::scale(glm::translate(glm::mat4(1.0f), at), glm::vec3(0.03f)), 0, 12));
        s.camera.width = s.camera.height = 40;
        s.gi.set("lpv.transport", "ordinates");
        s.gi.set("lpv.resolution", "16");  // llvmpipe runs the gl sweeps on the CPU: keep them small
        s.gi.set("lpv.backend", "cpu");
        const Image cpu = render(s, method);
        s.gi.set("lpv.backend", "gl");
        const Image gl = render(s, method);
        expectIndirectLayersAgree(cpu, gl, method);
    }
}

// With bricks left out (a 32^3 volume around the Cornell box stores only those near its walls),
// the gl sweeps add to the same stored cells and the apply pass reads the same through the tables.
TEST_F(LpvOrdinatesRender, GlSweepsMatchTheCpuSweepsWhereBricksAreLeftOut) {
    Scene s = test::cornellBox();
    s.camera.width = s.camera.height = 40;
    s.gi.set("lpv.transport", "ordinates");
    s.gi.set("lpv.resolution", "32");
    Image images[2];
    for (int gl = 0; gl < 2; ++gl) {
        s.gi.set("lpv.backend", gl ? "gl" : "cpu");
        FrameRenderer r(s, FrameOptions{}, "lpv");
        r.renderFrame();
        double stored = 0.0, grid = 0.0;
        for (const TechniqueStat& st : r.technique()->stats()) {
            if (st.name == "light_bricks") stored = st.value;
            if (st.name == "grid_bricks") grid = st.value;
        }
        EXPECT_GT(stored, 0.0);
        EXPECT_LT(stored, grid) << "every brick stored: nothing is left out";
        images[gl] = r.resolve();
    }
    expectIndirectLayersAgree(images[0], images[1], "lpv");
}

// A number of sweeps carried across updates runs on the cpu only; its refusal names the key.
TEST(LpvOrdinatesSettings, CarriedSweepsOnTheGlBackEndAreRefusedByName) {
    GiSettings gi;
    gi.set("lpv.transport", "ordinates");
    gi.set("lpv.backend", "gl");
    EXPECT_EQ(readLpvDesc(gi, true).transport, LpvTransport::Ordinates);
    gi.set("lpv.sweeps", "2");
    try {
        readLpvDesc(gi, true);
        FAIL() << "gl with carried sweeps accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("gi.lpv.sweeps"), std::string::npos) << e.what();
    }
    GiSettings odd;
    odd.set("lpv.ordinates_per_face", "3");
    EXPECT_THROW(readLpvDesc(odd, false), InputError);
}

TEST(LpvOrdinatesDump, VdbPrintReadsTheIrradianceCubes) {
    const std::string dir = test::makeTempDir("lpv-ordinates-dump");
    auto r = test::runVoxgi("dump cornell-box --method clpv --width 32 --height 32 --set lpv.transport=ordinates "
                            "--set lpv.resolution=16 --set lpv.backend=gl -o " + dir + "/o.vdb");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    auto print = test::runShell(std::string(VDB_PRINT_PROGRAM) + " " + dir + "/o.vdb");
    ASSERT_EQ(print.exitCode, 0) << print.output;
    for (const char* name : {"irradiance_px_L0", "irradiance_ny_L1", "irradiance_pz_L2"})
        EXPECT_NE(print.output.find(name), std::string::npos) << name << "\n" << print.output;
}
