// The direct-lit Cornell box, checked by properties that must hold, and the analytic cases of
// a point light over a plane and a sun, in physical units.
#include <gtest/gtest.h>

#include <cmath>

#include "render/frame/frame_renderer.h"
#include "gl/context.h"
#include "scenes/scene_loader.h"
#include "shaders/shared/constants.h"
#include "support/test_support.h"

using namespace voxgi;

namespace {

class DirectRender : public ::testing::Test {
protected:
    static void SetUpTestSuite() { test::useHeadlessContext(); }
};

Image render(const Scene& scene, int frames) {
    FrameRenderer r(scene, FrameOptions{});
    for (int i = 0; i < frames; ++i) r.renderFrame();
    return r.resolve();
}

// Mean of the beauty layer over a square window centred on (x, y).
glm::vec3 mean(const Image& img, int cx, int cy, int half) {
    glm::dvec3 sum(0.0);
    int n = 0;
    for (int y = cy - half; y <= cy + half; ++y)
        for (int x = cx - half; x <= cx + half; ++x) {
            sum += glm::dvec3(img.rgb("beauty", x, y));
            ++n;
        }
    return glm::vec3(sum / double(n));
}

// Pixel where a world point projects with the scene camera (top-left origin).
glm::ivec2 project(const Scene& s, glm::vec3 p) {
    glm::vec4 c = s.camera.projection() * s.camera.view() * glm::vec4(p, 1.0f);
    glm::vec2 ndc = glm::vec2(c) / c.w;
    return glm::ivec2(int((ndc.x * 0.5f + 0.5f) * float(s.camera.width)),
                      int((0.5f - ndc.y * 0.5f) * float(s.camera.height)));
}

}  // namespace

TEST_F(DirectRender, CornellBoxProperties) {
    Scene s = test::cornellBox();
    s.camera.width = s.camera.height = 128;
    Image img = render(s, 16);
    // Nothing NaN or negative anywhere.
    for (float v : img.find("beauty")->data) ASSERT_TRUE(std::isfinite(v) && v >= 0.0f);
    // The lit floor in front of the blocks is far brighter than the ceiling corners, which
    // the downward-facing light cannot see.
    glm::ivec2 floorPixel = project(s, {0.45f, 0.0f, 0.1f});
    glm::vec3 floor = mean(img, floorPixel.x, floorPixel.y, 2);
    glm::ivec2 corner = project(s, {0.03f, 0.54f, 0.54f});
    glm::vec3 ceilingCorner = mean(img, corner.x, corner.y, 1);
    EXPECT_GT(floor.r, 10.0f * std::max(ceilingCorner.r, 1e-6f));
    // Colour transport: the light is (17, 12, 4); on the white floor red > green > blue.
    EXPECT_GT(floor.r, floor.g);
    EXPECT_GT(floor.g, floor.b);
    // The red wall (x = 0.55) reflects far more red than green; the green wall the reverse.
    glm::ivec2 red = project(s, {0.553f, 0.27f, 0.3f}), green = project(s, {0.003f, 0.27f, 0.3f});
    glm::vec3 r = mean(img, red.x + 1, red.y, 0), g = mean(img, green.x - 1, green.y, 0);
    EXPECT_GT(r.r, 3.0f * r.g);
    EXPECT_GT(g.g, 1.5f * g.r);
    // The light itself shows its radiance.
    glm::ivec2 light = project(s, {0.278f, 0.548f, 0.28f});
    glm::vec3 l = img.rgb("beauty", light.x, light.y);
    EXPECT_NEAR(l.r, 17.0f, 0.5f);
}

TEST_F(DirectRender, PointLightOverPlaneMatchesInverseSquareCosine) {
    // Lambertian plane of albedo 0.5 at y = 0, point light of 10 W/sr at height 1, camera above.
    Scene s = parseSceneJson(R"({
      "camera": {"eye": [0, 3, 0.001], "target": [0, 0, 0], "fov": 60, "resolution": [64, 64]},
      "materials": {"m": {"albedo": 0.5}},
      "lights": [{"type": "point", "position": [0, 1, 0], "intensity": 10}],
      "meshes": [{"type": "quad", "material": "m", "corners": [[-5,0,5],[5,0,5],[5,0,-5],[-5,0,-5]]}]})",
                             "plane.json");
    Image img = render(s, 1);
    for (glm::vec3 p : {glm::vec3(0, 0, 0), glm::vec3(0.5f, 0, 0.3f), glm::vec3(-0.8f, 0, -0.6f)}) {
        glm::ivec2 px = project(s, p);
        float r2 = 1.0f + p.x * p.x + p.z * p.z;
        float cosTheta = 1.0f / std::sqrt(r2);
        float expected = 0.5f / shading::kPi * 10.0f * cosTheta / r2;  // rho/pi * I cos / r^2
        EXPECT_NEAR(img.rgb("beauty", px.x, px.y).g, expected, 0.03f * expected) << p.x << "," << p.z;
    }
}

TEST_F(DirectRender, SunIrradianceAndShadow) {
    // A sun of 2 W/m^2 at 60 degrees from the normal onto a plane of albedo 1: L = E cos / pi.
    Scene s = parseSceneJson(R"({
      "camera": {"eye": [0, 4, 0.001], "target": [0, 0, 0], "fov": 60, "resolution": [64, 64]},
      "materials": {"m": {"albedo": 1.0}},
      "lights": [{"type": "directional", "direction": [0.8660254, -0.5, 0], "irradiance": 2}],
      "meshes": [{"type": "quad", "material": "m", "corners": [[-5,0,5],[5,0,5],[5,0,-5],[-5,0,-5]]},
                 {"type": "box", "material": "m", "transform": {"translate": [0, 0.5, 0], "scale": 0.2}}]})",
                             "sun.json");
    Image img = render(s, 1);
    glm::ivec2 lit = project(s, {1.2f, 0.0f, 1.2f});
    EXPECT_NEAR(img.rgb("beauty", lit.x, lit.y).r, 2.0f * 0.5f / shading::kPi, 0.01f);
    // The box at height 0.4..0.6 casts its shadow towards +x: 0.5 / tan(30 deg) from below it.
    glm::ivec2 shadow = project(s, {0.5f / std::tan(0.5235988f), 0.0f, 0.0f});
    EXPECT_LT(img.rgb("beauty", shadow.x, shadow.y).r, 0.02f);
}

TEST_F(DirectRender, SpotLightConeAndInverseSquare) {
    // A spot of 8 W/sr pointing straight down from 2 m, cone 20..30 degrees, over albedo 1.
    Scene s = parseSceneJson(R"({
      "camera": {"eye": [0, 6, 0.001], "target": [0, 0, 0], "fov": 60, "resolution": [96, 96]},
      "materials": {"m": {"albedo": 1.0}},
      "lights": [{"type": "spot", "position": [0, 2, 0], "direction": [0, -1, 0], "intensity": 8,
                  "inner_angle": 20, "outer_angle": 30}],
      "meshes": [{"type": "quad", "material": "m", "corners": [[-5,0,5],[5,0,5],[5,0,-5],[-5,0,-5]]}]})",
                             "spot.json");
    Image img = render(s, 1);
    // Inside the inner cone: L = (1/pi) I cos / r^2.
    for (float x : {0.0f, 0.5f}) {
        glm::ivec2 px = project(s, {x, 0.0f, 0.0f});
        float r2 = 4.0f + x * x, cosTheta = 2.0f / std::sqrt(r2);
        EXPECT_NEAR(img.rgb("beauty", px.x, px.y).r, 8.0f * cosTheta / r2 / shading::kPi, 0.02f) << x;
    }
    // Outside the outer cone (tan 30 deg * 2 m = 1.15 m): dark.
    glm::ivec2 outside = project(s, {1.6f, 0.0f, 0.0f});
    EXPECT_EQ(img.rgb("beauty", outside.x, outside.y).r, 0.0f);
}
