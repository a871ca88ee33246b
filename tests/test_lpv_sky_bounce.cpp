// The LPV's sky bounce (gi/lpv/sky_bounce.h): the G-buffer face it makes carries exactly the
// flux the CPU's sky-volume lookup gives each surfel, the plan runs it only with a sky volume,
// and under a sky alone it is the LPV's only light.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "gi/lpv/sky_bounce.h"
#include "gi/methods.h"
#include "gi/raytrace/ray_tracer.h"
#include "gi/sky/sky_volume.h"
#include "gi/sky/sky_volume_texture.h"
#include "gl/context.h"
#include "gl/resources.h"
#include "render/frame/frame_plan.h"
#include "render/frame/frame_renderer.h"
#include "scenes/scene_loader.h"
#include "shaders/shared/gbuffer.h"
#include "support/test_support.h"

using namespace voxgi;

namespace {

// A ground, a wall and a box under a uniform sky, no lights.
Scene skyOnlyScene(bool sky = true) {
    std::string json = R"({
      "camera": {"eye": [0, 3, 6], "target": [0, 0.5, 0], "fov": 50, "resolution": [64, 48]},
      "materials": {"ground": {"albedo": [0.6, 0.5, 0.4]}, "wall": {"albedo": 0.8}},
      "meshes": [
        {"type": "quad", "material": "ground", "corners": [[-5, 0, 5], [5, 0, 5], [5, 0, -5], [-5, 0, -5]]},
        {"type": "box", "material": "wall", "transform": {"scale": [6, 3, 0.3], "translate": [0, 1.5, -2]}},
        {"type": "box", "material": "wall", "transform": {"scale": [1, 1, 1], "translate": [1.5, 0.5, 1]}}
      ])";
    if (sky) json += R"(, "sky": {"type": "constant", "radiance": [1.0, 0.9, 0.8]})";
    return parseSceneJson(json + "}", "sky-only.json");
}

}  // namespace

TEST(LpvSkyBounce, FaceFluxIsAlbedoTimesSkyIrradianceTimesFootprint) {
    test::useHeadlessContext();
    const Scene scene = skyOnlyScene();
    RayTracer tracer(scene);
    SkyVolumeDesc desc;
    desc.resolution = 8;
    desc.rays = 64;
    SkyVolume volume(tracer, desc);
    volume.update();
    const SkyVolumeTexture texture(volume);

    // A hand-made 8 x 4 G-buffer: points on the ground and on the wall's front, one miss.
    const int width = 8, height = 4;
    std::vector<glm::vec4> position(width * height), normal(width * height), albedo(width * height), emission(width * height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const std::size_t i = std::size_t(y * width + x);
            shading::GBufferSurface s;
            const bool wall = y >= 2;
            s.position = wall ? glm::vec3(-2.5f + 0.6f * float(x), 0.3f + 0.7f * float(y - 2), -1.85f)
                              : glm::vec3(-3.0f + 0.8f * float(x), 0.0f, 2.0f - 1.5f * float(y));
            s.normal = wall ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
            s.albedo = wall ? glm::vec3(0.8f) : glm::vec3(0.6f, 0.5f, 0.4f);
            s.emission = glm::vec3(0.0f);
            s.roughness = 1.0f;
            s.metallic = 0.0f;
            s.specular = 0.0f;
            const shading::GBufferTexels t = shading::encodeGBuffer(s);
            position[i] = (x == 3 && y == 1) ? glm::vec4(0.0f) : t.position;
            normal[i] = t.normal;
            albedo[i] = t.albedo;
            emission[i] = t.emission;
        }
    std::vector<gl::Handle> textures;
    for (const auto* data : {&position, &normal, &albedo, &emission}) {
        textures.push_back(gl::createTexture(GL_TEXTURE_2D, GL_RGBA32F, width, height));
        glTextureSubImage2D(textures.back().id(), 0, 0, 0, width, height, GL_RGBA, GL_FLOAT, data->data());
    }
    GBufferView g;
    g.position = textures[0].id();
    g.normal = textures[1].id();
    g.albedo = textures[2].id();
    g.emission = textures[3].id();
    g.width = width;
    g.height = height;
    g.eye = scene.camera.eye;
    g.viewProjection = scene.camera.projection() * scene.camera.view();
    g.fovYDegrees = scene.camera.fovYDegrees;

    // A face as wide as the G-buffer: texel (x, y) reads pixel (x, y) of the wide G-buffer's
    // columns 0..7 only when size = 8 maps rows 0..7 onto its 4 rows (two texels a row).
    SkyBounceFace bounce(8);
    const SurfelSource surfels = readSurfels(bounce.render(g, texture));
    ASSERT_EQ(surfels.surfels.size(), 2u * (width * height - 1));  // every hit pixel twice, the miss never
    const glm::vec3 forward = glm::normalize(scene.camera.target - scene.camera.eye);
    const float pixelEdge = 2.0f * std::tan(0.5f * glm::radians(scene.camera.fovYDegrees)) / float(height);
    const float texelSolidAngle = pixelEdge * pixelEdge * float(width * height) / 64.0f;
    int lit = 0;
    for (const Surfel& s : surfels.surfels) {
        const glm::vec3 d = s.position - g.eye;
        const float dist = glm::length(d);
        const float c = glm::dot(d / dist, forward);
        const float area = texelSolidAngle * c * c * c * dist * dist / std::max(std::abs(glm::dot(s.normal, d / dist)), 0.05f);
        const glm::vec3 expected = s.albedo * volume.sampleIrradiance(s.position, s.normal) * area;
        SCOPED_TRACE(testing::Message() << "surfel at (" << s.position.x << ", " << s.position.y << ", " << s.position.z << ")");
        EXPECT_NEAR(s.area, area, 1e-4f * area);
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(s.flux[k], expected[k], 1e-3f * expected[k] + 1e-9f);
        lit += expected.g > 0.0f ? 1 : 0;
    }
    EXPECT_GT(lit, 50);  // the sky reaches the surfels (open cells around them)
}

TEST(LpvSkyBounce, RunsOnlyWithTheSkyVolume) {
    test::useHeadlessContext();
    const FramePlan withSky = planFrame(skyOnlyScene(), "clpv", 1);
    EXPECT_TRUE(withSky.runs("sky_volume"));
    EXPECT_TRUE(withSky.technique.runs("lpv.sky_bounce"));
    EXPECT_TRUE(withSky.technique.runs("lpv.propagate"));  // no lights: the sky is the light
    EXPECT_FALSE(withSky.technique.runs("lpv.rsm"));
    const FramePlan noSky = planFrame(skyOnlyScene(false), "clpv", 1);
    EXPECT_FALSE(noSky.technique.runs("lpv.sky_bounce"));
    EXPECT_FALSE(noSky.technique.runs("lpv.propagate"));
    Scene off = skyOnlyScene();
    off.gi.set("lpv.sky_bounce_size", "0");
    EXPECT_FALSE(planFrame(off, "lpv", 1).technique.runs("lpv.sky_bounce"));
    off = skyOnlyScene();
    off.gi.set("sky.light", "false");
    EXPECT_FALSE(planFrame(off, "clpv", 1).technique.runs("lpv.sky_bounce"));
}

TEST(LpvSkyBounce, SkyAloneLightsTheIndirectLayerOnBothBackEnds) {
    test::useHeadlessContext();
    auto indirectSum = [](Scene scene, const char* backend, const char* size) {
        scene.gi.set("lpv.backend", backend);
        scene.gi.set("lpv.sky_bounce_size", size);
        scene.gi.set("lpv.resolution", "16");
        FrameRenderer r(scene, FrameOptions{}, "lpv");
        r.renderFrame();
        const Image img = r.resolve();
        double sum = 0.0;
        for (float v : img.find("indirect")->data) sum += double(v);
        return sum;
    };
    const double none = indirectSum(skyOnlyScene(), "cpu", "0");
    const double cpu = indirectSum(skyOnlyScene(), "cpu", "64");
    const double gpu = indirectSum(skyOnlyScene(), "gl", "64");
    EXPECT_EQ(none, 0.0);
    EXPECT_GT(cpu, 0.0);
    EXPECT_NEAR(gpu, cpu, 0.02 * cpu);
}
