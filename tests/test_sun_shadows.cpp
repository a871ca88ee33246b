// The sun's cascaded soft shadows (render/frame/sun_cascades.h, shaders/frame/sun_shadow.glsl):
// cascades that hold still as the camera moves and cover what it sees, and a thin pole's
// shadow in a big scene against the path tracer, which samples the same sun disc.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "gi/pathtrace/path_tracer.h"
#include "gl/context.h"
#include "gl/resources.h"
#include "render/frame/frame_renderer.h"
#include "render/frame/sun_cascades.h"
#include "scenes/scene_loader.h"
#include "support/test_support.h"

using namespace voxgi;

namespace {

Camera testCamera() {
    Camera c;
    c.eye = {3.0f, 2.0f, 5.0f};
    c.target = {0.0f, 1.0f, 0.0f};
    c.fovYDegrees = 50.0f;
    c.width = 320;
    c.height = 200;
    c.nearPlane = 0.05f;
    c.farPlane = 500.0f;
    return c;
}

Bounds bigScene() {
    Bounds b;
    b.extend({-100.0f, 0.0f, -100.0f});
    b.extend({100.0f, 20.0f, 100.0f});
    return b;
}

// Where world point p falls in cascade c's map, in texels.
glm::vec2 texelOf(const SunCascade& c, glm::vec3 p, int mapSize) {
    return glm::vec2(c.worldToMap * glm::vec4(p, 1.0f)) * float(mapSize);
}

}  // namespace

TEST(SunCascades, HoldStillAsTheCameraMovesAndTurns) {
    const glm::vec3 sun = glm::normalize(glm::vec3(-0.4f, -0.8f, 0.3f));
    const int mapSize = 2048;
    const Camera a = testCamera();
    const SunCascades fa = fitSunCascades(a, sun, bigScene(), mapSize, 4);
    ASSERT_EQ(fa.cascades.size(), 4u);
    // Moved by a fraction of a texel and turned a little: each map's texel grid stays where it
    // was in the world (a world point moves by whole texels), and texels keep their size.
    Camera b = a;
    b.eye += glm::vec3(0.0123f, -0.0071f, 0.0043f);
    b.target += glm::vec3(0.3f, 0.1f, -0.2f);
    const SunCascades fb = fitSunCascades(b, sun, bigScene(), mapSize, 4);
    ASSERT_EQ(fb.cascades.size(), 4u);
    const glm::vec3 probe(1.234f, 0.5f, -2.345f);
    for (std::size_t c = 0; c < 4; ++c) {
        SCOPED_TRACE(c);
        EXPECT_FLOAT_EQ(fa.cascades[c].texelWorld, fb.cascades[c].texelWorld);
        const glm::vec2 d = texelOf(fb.cascades[c], probe, mapSize) - texelOf(fa.cascades[c], probe, mapSize);
        EXPECT_NEAR(d.x, std::round(d.x), 2e-2f);
        EXPECT_NEAR(d.y, std::round(d.y), 2e-2f);
        if (c > 0) {
            EXPECT_GT(fa.cascades[c].texelWorld, fa.cascades[c - 1].texelWorld);
        }
    }
}

TEST(SunCascades, CoverEveryPointTheCameraSees) {
    const glm::vec3 sun = glm::normalize(glm::vec3(0.2f, -1.0f, 0.1f));
    const Camera cam = testCamera();
    const Bounds scene = bigScene();
    const SunCascades fit = fitSunCascades(cam, sun, scene, 1024, 4);
    const glm::mat4 inverse = glm::inverse(cam.projection() * cam.view());
    const glm::vec3 forward = glm::normalize(cam.target - cam.eye);
    int checked = 0;
    for (int i = 0; i <= 20; ++i)
        for (int j = 0; j <= 20; ++j)
            for (float depth : {-0.999f, 0.0f, 0.9f, 0.99f, 0.9999f}) {
                glm::vec4 w = inverse * glm::vec4(-1.0f + 0.1f * float(i), -1.0f + 0.1f * float(j), depth, 1.0f);
                const glm::vec3 p = glm::vec3(w) / w.w;
                if (glm::any(glm::lessThan(p, scene.min)) || glm::any(glm::greaterThan(p, scene.max))) continue;
                ++checked;
                // The cascade its view distance falls in holds it inside its map and depth range.
                const float along = glm::dot(p - cam.eye, forward);
                std::size_t c = 0;
                while (c + 1 < fit.cascades.size() && along > fit.cascades[c].splitFar) ++c;
                const glm::vec3 m = glm::vec3(fit.cascades[c].worldToMap * glm::vec4(p, 1.0f));
                EXPECT_TRUE(glm::all(glm::greaterThanEqual(m, glm::vec3(0.0f))) && glm::all(glm::lessThanEqual(m, glm::vec3(1.0f))))
                    << "point (" << p.x << ", " << p.y << ", " << p.z << ") in cascade " << c << " at (" << m.x << ", " << m.y
                    << ", " << m.z << ")";
            }
    EXPECT_GT(checked, 500);
}

namespace {

// The shipped thin-pole scene (a 3 cm pole 6 m tall on a 400 m ground, a sun of 0.53 degrees
// along -x) seen from straight above its shadow: image columns run along the shadow (world -x
// from x = -0.4 to -4.4), rows across it (0.5 m of z, 7.8 mm per row).
Scene poleShadowScene() {
    Scene s = loadSceneFile(std::string(VOXGI_SOURCE_DIR) + "/scenes/thin-pole.json");
    s.camera.eye = {-2.4f, 6.0f, 0.0f};
    s.camera.target = {-2.4f, 0.0f, 0.0f};
    s.camera.up = {0.0f, 0.0f, 1.0f};
    s.camera.fovYDegrees = glm::degrees(2.0f * std::atan(0.25f / 6.0f));
    s.camera.width = 256;
    s.camera.height = 64;
    return s;
}

struct ShadowProfile {
    double mass = 0.0;      // the shadow's integral across it: metres of full shadow
    double darkest = 1.0;   // the lowest lit fraction across it
};

// The shadow across columns [x0, x1) of the direct layer: per column, the lit fraction of each
// row against the column's unshadowed ends, summed (times the row's width) and its minimum,
// averaged over the columns.
ShadowProfile profile(const Image& img, int x0, int x1) {
    const double rowWidth = 0.5 / double(img.height());
    ShadowProfile p;
    p.darkest = 0.0;
    for (int x = x0; x < x1; ++x) {
        double lit = 0.0;
        int n = 0;
        for (int y = 0; y < img.height(); ++y)
            if (y < 10 || y >= img.height() - 10) {
                lit += double(img.rgb("direct", x, y).g);
                ++n;
            }
        lit /= double(n);
        double mass = 0.0, darkest = 1.0;
        for (int y = 0; y < img.height(); ++y) {
            const double f = double(img.rgb("direct", x, y).g) / lit;
            mass += (1.0 - f) * rowWidth;
            darkest = std::min(darkest, f);
        }
        p.mass += mass / double(x1 - x0);
        p.darkest += darkest / double(x1 - x0);
    }
    return p;
}

}  // namespace

TEST(SunShadows, ThinPoleShadowMatchesThePathTracer) {
    test::useHeadlessContext();
    const Scene scene = poleShadowScene();
    FrameRenderer raster(scene, FrameOptions{});
    for (int i = 0; i < 8; ++i) raster.renderFrame();
    const Image fast = raster.resolve();

    PathTracerOptions options;
    options.maxBounces = 1;
    PathTracer tracer(scene, options);
    tracer.render(128);
    const Image reference = tracer.image();

    // Four stretches along the shadow: near the pole's foot the umbra is the pole's 3 cm; toward
    // the far end (the pole 6.5 m from the ground along the light) the sun's disc spreads
    // it over 6 cm, with no umbra left.
    for (int section = 0; section < 4; ++section) {
        const int x0 = section * 64 + 4, x1 = section * 64 + 60;
        const ShadowProfile r = profile(reference, x0, x1), f = profile(fast, x0, x1);
        SCOPED_TRACE(testing::Message() << "columns " << x0 << ".." << x1 << ": reference mass " << r.mass << " m, darkest "
                                        << r.darkest << "; raster mass " << f.mass << " m, darkest " << f.darkest);
        // The light a thin caster takes away is its width, however soft the shadow.
        EXPECT_NEAR(r.mass, 0.03, 0.003);
        EXPECT_NEAR(f.mass, r.mass, 0.15 * r.mass);
        EXPECT_NEAR(f.darkest, r.darkest, 0.12);
    }
    // The penumbra widens along the shadow: full shadow at the foot, a quarter of the sun's
    // disc still seen through the middle of it near the far end.
    EXPECT_LT(profile(reference, 4, 60).darkest, 0.1);
    EXPECT_GT(profile(reference, 196, 252).darkest, 0.2);
}

// A guard band (a method's plan draws surfaces beyond the picture's edges, docs/isr.md) leaves
// the picture's sun shadows as they were: its cascades are fitted to the picture, not to the
// wider targets, and the soft shadows' noise follows the picture's pixels.
TEST(SunShadows, GuardBandLeavesThePicturesShadowsAsTheyWere) {
    test::useHeadlessContext();
    FrameOptions options;
    options.jitter = false;
    auto direct = [&](const char* band) {
        Scene scene = poleShadowScene();
        scene.gi.set("isr.guard_band", band);
        FrameRenderer r(scene, options, "isr");
        r.renderFrame();
        return r.resolve().find("direct")->data;
    };
    const std::vector<float> plain = direct("0"), banded = direct("0.5");
    ASSERT_EQ(plain.size(), banded.size());
    const float lit = *std::max_element(plain.begin(), plain.end());
    double shadowed = 0.0, maxDifference = 0.0;
    for (std::size_t i = 0; i < plain.size(); ++i) {
        maxDifference = std::max(maxDifference, std::fabs(double(banded[i]) - double(plain[i])));
        shadowed += plain[i] < 0.1f * lit;
    }
    EXPECT_GT(shadowed, 0.0);  // the pole's umbra is in the picture
    EXPECT_LT(maxDifference, 1e-4) << "max difference";
}

// The band's own surfaces are shadowed too. Under a roof over the whole ground nothing the
// targets see is lit; from this camera (a 20 degree field 6 m up, looking down at 30 degrees)
// some of the band's ground lies outside every map fitted to the picture (267 pixels lit
// without it): one more map over the targets' whole view shadows them.
TEST(SunShadows, GuardBandSurfacesAreShadowed) {
    test::useHeadlessContext();
    Scene scene = parseSceneJson(R"({
      "camera": {"eye": [0, 6, 0], "target": [0.612, 5.5, 0.612], "fov": 20, "resolution": [64, 64], "near": 0.05, "far": 600},
      "materials": {"grey": {"albedo": [0.5, 0.5, 0.5]}},
      "lights": [{"type": "directional", "direction": [-0.6, -0.8, 0.0], "irradiance": [3, 3, 3]}],
      "meshes": [
        {"type": "quad", "material": "grey", "corners": [[-200, 0, 200], [200, 0, 200], [200, 0, -200], [-200, 0, -200]]},
        {"type": "quad", "material": "grey", "corners": [[-300, 10, 300], [300, 10, 300], [300, 10, -300], [-300, 10, -300]]}
      ]
    })", "roofed-ground.json");
    scene.gi.set("isr.guard_band", "0.5");
    FrameOptions options;
    options.jitter = false;
    FrameRenderer r(scene, options, "isr");
    r.renderFrame();
    const int w = 128, h = 128;  // 64 x 64 and half of each beyond every edge
    const std::vector<float> direct = gl::readTexture(r.textures().direct, w, h, 4);
    const std::vector<float> position = gl::readTexture(r.textures().position, w, h, 4);
    int ground = 0, lit = 0;
    for (int i = 0; i < w * h; ++i) {
        if (position[4 * i + 3] <= 0.0f || position[4 * i + 1] > 1.0f) continue;  // sky or roof
        ++ground;
        lit += direct[4 * i + 1] > 1e-4f;
    }
    EXPECT_GT(ground, w * h / 4);
    EXPECT_EQ(lit, 0);
}
