// The sky-lighting volume (gi/sky/sky_volume.h) and the frame's sky_light pass: an open ground
// under a constant sky gets pi L (and the pass shows albedo L), the inside of a closed box gets
// nothing, a budgeted build equals a whole one, the plan leaves the pass out where the sky is
// absent or turned off, only the bricks a surface's lookup reaches are stored, and DDGI's probes
// carry only the sky's bounce.
#include <gtest/gtest.h>

#include <cstdlib>

#include <glm/gtc/matrix_transform.hpp>

#include "gi/raytrace/ray_tracer.h"
#include "gi/sky/sky_volume.h"
#include "render/frame/frame_plan.h"
#include "render/frame/frame_renderer.h"
#include "scenes/primitives.h"
#include "scenes/sky_model.h"
#include "shaders/shared/constants.h"
#include "support/test_support.h"

using namespace voxgi;

namespace {

// A 20 m ground and a 2 m box standing on it, under a constant sky, no lights.
Scene groundUnderSky() {
    Scene s;
    Material m;
    m.albedo = glm::vec3(0.5f, 0.4f, 0.3f);
    s.materials = {m};
    s.meshes.push_back(
        makeQuad({glm::vec3(-10, 0, 10), glm::vec3(10, 0, 10), glm::vec3(10, 0, -10), glm::vec3(-10, 0, -10)}, 0));
    s.meshes.push_back(makeBox(glm::translate(glm::mat4(1.0f), glm::vec3(0, 1, 0)) * glm::scale(glm::mat4(1.0f), glm::vec3(2.0f)), 0, false));
    s.sky.enabled = true;
    s.sky.radiance = glm::vec3(0.2f, 0.3f, 0.5f);
    s.camera.eye = glm::vec3(6.0f, 5.0f, 6.0f);
    s.camera.target = glm::vec3(4.0f, 0.0f, 4.0f);
    s.camera.width = s.camera.height = 32;
    return s;
}

}  // namespace

TEST(SkyVolume, OpenGroundGetsPiTimesTheSkyRadiance) {
    const Scene s = groundUnderSky();
    RayTracer tracer(s);
    SkyVolume volume(tracer, SkyVolumeDesc{});
    ASSERT_TRUE(volume.update());
    // Far from the box the ground sees the whole upper hemisphere: E = pi L (the hemisphere's
    // radiance has no band-2 part and the cosine lobe none above band 2 but even ones, so 3-band
    // SH loses only the Monte Carlo error of 128 directions).
    const glm::vec3 e = volume.sampleIrradiance(glm::vec3(7.0f, 0.0f, -7.0f), glm::vec3(0, 1, 0));
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(e[k], shading::kPi * s.sky.radiance[k], 0.03f * shading::kPi * s.sky.radiance[k]);
    // The ground beside the box sees less sky than the open ground.
    EXPECT_LT(volume.sampleIrradiance(glm::vec3(1.2f, 0.0f, 0.0f), glm::vec3(0, 1, 0)).b, 0.9f * e.b);
}

TEST(SkyVolume, InsideAClosedBoxThereIsNoSky) {
    Scene s = groundUnderSky();
    s.meshes.push_back(makeBox(glm::translate(glm::mat4(1.0f), glm::vec3(0, 3, -5)) * glm::scale(glm::mat4(1.0f), glm::vec3(4.0f)), 0, true));
    s.meshes.push_back(makeBox(glm::translate(glm::mat4(1.0f), glm::vec3(0, 3, -5)) * glm::scale(glm::mat4(1.0f), glm::vec3(4.4f)), 0, false));
    RayTracer tracer(s);
    SkyVolumeDesc d;
    d.resolution = 24;
    SkyVolume volume(tracer, d);
    volume.update();
    const glm::vec3 floor = volume.sampleIrradiance(glm::vec3(0.3f, 1.01f, -5.2f), glm::vec3(0, 1, 0));
    EXPECT_LT(floor.b, 1e-3f * shading::kPi * s.sky.radiance.b) << floor.b;
}

TEST(SkyVolume, ABudgetedBuildEqualsAWholeOne) {
    const Scene s = groundUnderSky();
    RayTracer tracer(s);
    SkyVolumeDesc d;
    d.resolution = 16;
    SkyVolume whole(tracer, d), budgeted(tracer, d);
    whole.update();
    int calls = 0;
    while (!budgeted.update(1e-6)) ++calls;
    EXPECT_GT(calls, 2);  // one batch of cells per call at this budget
    EXPECT_EQ(whole.packed(), budgeted.packed());
}

TEST(SkyVolume, StoresOnlyTheBricksASurfaceLookupReaches) {
    // A 20 m ground and a 16 m tower: most of the grid is air no surface's lookup reads.
    Scene s = groundUnderSky();
    s.meshes.push_back(makeBox(glm::translate(glm::mat4(1.0f), glm::vec3(-6, 8, 6)) * glm::scale(glm::mat4(1.0f), glm::vec3(1, 16, 1)), 0));
    RayTracer tracer(s);
    SkyVolumeDesc d;
    d.resolution = 40;
    SkyVolume volume(tracer, d);
    ASSERT_TRUE(volume.update());
    const glm::ivec3 b = volume.brickDims();
    const std::size_t bricks = std::size_t(b.x) * std::size_t(b.y) * std::size_t(b.z);
    EXPECT_LT(volume.activeBricks(), bricks / 3) << volume.activeBricks() << " of " << bricks;
    EXPECT_EQ(volume.packed().size(), std::size_t(volume.atlasSize().x) * std::size_t(volume.atlasSize().y) *
                                          std::size_t(volume.atlasSize().z));
    // Every cell a lookup on any triangle reads is stored (and the one far above is not).
    int checked = 0;
    for (const Mesh& m : s.meshes)
        for (std::size_t t = 0; t < m.triangleCount(); ++t) {
            const glm::vec3 a = m.positions[m.indices[3 * t]], e1 = m.positions[m.indices[3 * t + 1]] - a,
                            e2 = m.positions[m.indices[3 * t + 2]] - a;
            const glm::vec3 n = glm::normalize(glm::cross(e1, e2));
            for (int i = 0; i <= 12; ++i)
                for (int j = 0; i + j <= 12; ++j)
                    for (float side : {1.0f, -1.0f}) {
                        const glm::vec3 p = a + e1 * (float(i) / 12.0f) + e2 * (float(j) / 12.0f);
                        const shading::SkyVolumeTaps taps =
                            shading::skyVolumeTaps(p + side * n * (0.5f * volume.cellSize()), volume.origin(), volume.cellSize());
                        for (int corner = 0; corner < 8; ++corner) {
                            const glm::ivec3 c = glm::clamp(taps.base + glm::ivec3(corner & 1, (corner >> 1) & 1, corner >> 2),
                                                            glm::ivec3(0), volume.dims() - 1);
                            EXPECT_NE(volume.cell(c), nullptr) << c.x << " " << c.y << " " << c.z;
                            ++checked;
                        }
                    }
        }
    EXPECT_GT(checked, 10000);
    const glm::vec3 high = (glm::vec3(6, 15, -6) - volume.origin()) / volume.cellSize();
    EXPECT_EQ(volume.cell(glm::ivec3(high)), nullptr);
}

namespace {
class SkyLightPass : public ::testing::Test {
protected:
    static void SetUpTestSuite() { test::useHeadlessContext(); }
};
}  // namespace

TEST_F(SkyLightPass, TheFrameShowsAlbedoTimesTheSkyOnOpenGround) {
    Scene s = groundUnderSky();
    s.camera.eye = glm::vec3(6.0f, 3.0f, -6.0f);
    s.camera.target = glm::vec3(7.0f, 0.0f, -7.0f);
    FrameRenderer r(s, FrameOptions{}, "direct");
    ASSERT_TRUE(r.plan().runs("sky_light"));
    r.renderFrame();
    const Image image = r.resolve();
    // The centre pixel looks at open ground: diffuse albedo / pi * pi L.
    const glm::vec3 c = image.rgb("direct", 16, 16);
    const glm::vec3 expected = s.materials[0].albedo * s.sky.radiance;
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(c[k], expected[k], 0.03f * expected[k]);
    // The same lookup on the CPU at that pixel's surface point.
    RayTracer tracer(s);
    SkyVolume volume(tracer, SkyVolumeDesc{});
    volume.update();
    const glm::vec3 cpu = s.materials[0].albedo / shading::kPi *
                          volume.sampleIrradiance(glm::vec3(7.0f, 0.0f, -7.0f), glm::vec3(0, 1, 0));
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(c[k], cpu[k], 0.01f * cpu[k]);
}

// The sun moves (the viewer, followSun): the frame uploads the new sky's table at once and traces
// the sky volume again over frames within sky.update_ms, lit meanwhile by the old volume. Once it
// is whole the frame is what a renderer made under the new sky draws, for the sky_light pass
// and for CLPV, whose sky bounce reads the volume.
TEST_F(SkyLightPass, AMovedSunTracesTheVolumeAgainOverFrames) {
    for (const char* method : {"direct", "clpv"}) {
        Scene s = groundUnderSky();
        s.sky = makeAtmosphere(AtmosphereDesc{glm::normalize(glm::vec3(0.2f, -1.0f, 0.3f)), 3.0f, 0.3f, 10.0f, 64}).sky;
        Light sun;
        sun.type = LightType::Directional;
        sun.name = "sun";
        sun.direction = s.sky.atmosphere.sunDirection;
        s.lights.push_back(sun);
        s.camera.width = s.camera.height = 16;
        s.gi.set("sky.resolution", "8");
        s.gi.set("sky.update_ms", "0.001");  // one batch of cells a frame
        s.gi.set("lpv.resolution", "8");
        FrameOptions options;
        options.jitter = false;
        FrameRenderer moving(s, options, method);
        moving.renderFrame();
        s.lights[0].direction = glm::normalize(glm::vec3(0.8f, -0.5f, -0.2f));
        ASSERT_TRUE(followSun(s));
        FrameRenderer fresh(s, options, method);
        fresh.renderFrame();
        const Image expected = fresh.resolve();
        auto difference = [&](const Image& x) {
            double sum = 0.0, total = 0.0;
            for (const char* layer : {"direct", "indirect"}) {
                const std::vector<float>&a = x.find(layer)->data, &b = expected.find(layer)->data;
                for (std::size_t i = 0; i < a.size(); ++i) {
                    sum += std::fabs(double(a[i]) - double(b[i]));
                    total += std::fabs(double(b[i]));
                }
            }
            return sum / total;
        };
        int frames = 0;
        double first = 0.0, last = 1.0;
        while (frames < 400 && last > 1e-5) {
            moving.resetAccumulation();
            moving.renderFrame();
            last = difference(moving.resolve());
            if (frames++ == 0) first = last;
        }
        EXPECT_GT(frames, 2) << method;     // spread over frames
        EXPECT_GT(first, 1e-3) << method;   // the old volume lit them meanwhile
        EXPECT_LE(last, 1e-5) << method;    // then the new one, as a fresh renderer's
    }
}

// DDGI in a frame that lights surfaces with the sky volume: its indirect layer holds only light
// that bounced, as the path tracer's does. Open ground far from the box has almost none (it
// was albedo x L, the sky's direct light, when the probes' missed rays saw the sky), and the
// box's side gets the ground's sky light bounced: about rho_box rho_ground L / 2 from the half
// of its view that is ground lit by the whole sky.
TEST_F(SkyLightPass, DdgiCarriesOnlyTheSkysBounce) {
    Scene s = groundUnderSky();
    s.gi.set("ddgi.hysteresis", "0.5");
    s.camera.eye = glm::vec3(6.0f, 3.0f, -6.0f);
    s.camera.target = glm::vec3(7.0f, 0.0f, -7.0f);
    const glm::vec3 rho = s.materials[0].albedo;
    {
        FrameRenderer r(s, FrameOptions{}, "ddgi");
        ASSERT_TRUE(r.plan().runs("sky_light"));
        for (int f = 0; f < 12; ++f) r.renderFrame();
        const Image image = r.resolve();
        const glm::vec3 ground = image.rgb("indirect", 16, 16);
        EXPECT_LT(ground.b, 0.05f * rho.b * s.sky.radiance.b) << ground.b;
        EXPECT_GT(image.rgb("direct", 16, 16).b, 0.9f * rho.b * s.sky.radiance.b);
    }
    s.camera.eye = glm::vec3(6.0f, 1.0f, 0.0f);
    s.camera.target = glm::vec3(0.0f, 1.0f, 0.0f);
    // Embree on the CPU, and the GPU's march through the voxelized scene (its sky lookup is
    // shaders/common/sky_volume.glsl).
    for (const char* trace : {"triangles", "volume"}) {
        s.gi.set("ddgi.trace", trace);
        FrameRenderer r(s, FrameOptions{}, "ddgi");
        for (int f = 0; f < 12; ++f) r.renderFrame();
        const Image image = r.resolve();
        const glm::vec3 side = image.rgb("indirect", 16, 16), expected = 0.5f * rho * rho * s.sky.radiance;
        for (int k = 0; k < 3; ++k) {
            EXPECT_GT(side[k], 0.4f * expected[k]) << trace << " " << k;
            EXPECT_LT(side[k], 1.2f * expected[k]) << trace << " " << k;
        }
    }
}

TEST(SkyLightPlan, LeftOutWithoutSkyAndWhenTurnedOff) {
    Scene s = groundUnderSky();
    EXPECT_TRUE(planFrame(s, "direct", 1).runs("sky_light"));
    EXPECT_TRUE(planFrame(s, "clpv", 1).runs("sky_light"));
    EXPECT_TRUE(planFrame(s, "ddgi", 1).runs("sky_light"));  // its probes carry only the bounce
    s.gi.set("sky.light", "false");
    EXPECT_FALSE(planFrame(s, "direct", 1).runs("sky_light"));
    s.gi = GiSettings{};
    s.sky.enabled = false;
    EXPECT_FALSE(planFrame(s, "direct", 1).runs("sky_light"));
}

TEST(SkyVolumeDump, GridsEveryToolReads) {
    const std::string dir = test::makeTempDir("sky-dump");
    auto r = test::runVoxgi("dump " + test::sourcePath("scenes/outdoor.json") + " --sky --set sky.resolution=16 -o " + dir +
                            "/sky.vdb");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    r = test::runVoxgi("inspect " + dir + "/sky.vdb");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("27 grid(s)"), std::string::npos) << r.output;
    for (const char* grid : {"sky_sh_r_0", "sky_sh_g_4", "sky_sh_b_8"}) EXPECT_NE(r.output.find(grid), std::string::npos) << grid;
    const std::string python = test::pythonWith("pyopenvdb");
    if (!python.empty()) {
        const int status = std::system((python + " -c \"import pyopenvdb as v; g = v.readAll('" + dir +
                                        "/sky.vdb')[0]; assert len(g) == 27, len(g)\"")
                                           .c_str());
        EXPECT_EQ(status, 0) << "pyopenvdb.readAll";
    }
    // A scene without a sky has nothing to dump.
    r = test::runVoxgi("dump cornell-box --sky -o " + dir + "/none.vdb");
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.output.find("--sky: cornell-box has no sky"), std::string::npos) << r.output;
    EXPECT_FALSE(test::fileExists(dir + "/none.vdb"));
}
