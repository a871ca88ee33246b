// Texture mip pyramids and ray-cone level of detail (gi/raytrace/texture_pyramid.h), and the
// cone-averaged albedo lookup of RayTracer (used by DDGI probe rays).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "gi/raytrace/ray_tracer.h"
#include "gi/raytrace/texture_pyramid.h"
#include "scenes/scene.h"
#include "shaders/shared/constants.h"

using namespace voxgi;

namespace {

// A width x height checkerboard of black and white squares `square` texels wide.
Texture checkerboard(int width, int height, int square) {
    Texture t;
    t.path = "checker";
    t.width = width;
    t.height = height;
    t.rgba.resize(std::size_t(width) * std::size_t(height) * 4);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            std::uint8_t v = ((x / square + y / square) % 2) ? 255 : 0;
            std::uint8_t* p = &t.rgba[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * 4];
            p[0] = p[1] = p[2] = v;
            p[3] = 255;
        }
    return t;
}

}  // namespace

TEST(TexturePyramid, SrgbCodesRoundTrip) {
    for (int c = 0; c < 256; ++c) EXPECT_EQ(linearToSrgb(srgbToLinear(std::uint8_t(c))), c);
    EXPECT_EQ(linearToSrgb(-1.0f), 0);
    EXPECT_EQ(linearToSrgb(2.0f), 255);
    EXPECT_EQ(linearToSrgb(NAN), 0);
}

TEST(TexturePyramid, LevelsHalveAndKeepTheMeanInLinearSpace) {
    Texture t = checkerboard(64, 16, 1);
    TexturePyramid pyramid(t);
    ASSERT_EQ(pyramid.levels(), 7);  // 64x16, 32x8, 16x4, 8x2, 4x1, 2x1, 1x1
    EXPECT_EQ(pyramid.width(1), 32);
    EXPECT_EQ(pyramid.height(1), 8);
    EXPECT_EQ(pyramid.width(6), 1);
    EXPECT_EQ(pyramid.height(6), 1);
    // Black and white average to linear 0.5 (sRGB code 188), not code 128: filtering is done
    // in linear space.
    for (int l = 0; l < pyramid.levels(); ++l) EXPECT_NEAR(pyramid.levelMean(l).x, 0.5f, 0.004f) << "level " << l;
    EXPECT_NEAR(pyramid.sample(glm::vec2(0.3f, 0.6f), 100).y, 0.5f, 0.004f);
    // Above level 0 a lookup is the nearest texel of the level.
    const glm::vec3 texel = pyramid.sample(glm::vec2(0.3f, 0.6f), 1);
    EXPECT_NEAR(texel.x, 0.5f, 0.004f);
    EXPECT_EQ(texel, pyramid.sample(glm::vec2(0.3f + 0.2f / 32.0f, 0.6f), 1));
}

TEST(TexturePyramid, OddSidesDropNoTexel) {
    // A 3x3 image whose last column is white: level 1 (1x1) averages all nine texels.
    Texture t = checkerboard(3, 3, 100);  // all black
    for (int y = 0; y < 3; ++y)
        for (int c = 0; c < 3; ++c) t.rgba[(std::size_t(y) * 3 + 2) * 4 + std::size_t(c)] = 255;
    TexturePyramid pyramid(t);
    ASSERT_EQ(pyramid.levels(), 2);
    EXPECT_NEAR(pyramid.levelMean(1).x, 1.0f / 3.0f, 0.004f);
}

TEST(TexturePyramid, LevelZeroIsTheFullResolutionLookup) {
    Texture t = checkerboard(32, 32, 4);
    TexturePyramid pyramid(t);
    for (float u : {0.01f, 0.37f, 0.5f, 0.99f, -0.25f, 3.7f})
        for (float v : {0.02f, 0.5f, 0.77f}) {
            glm::vec3 a = pyramid.sample(glm::vec2(u, v), 0), b = t.sampleLinear(glm::vec2(u, v));
            EXPECT_EQ(a, b);
            EXPECT_EQ(pyramid.sample(glm::vec2(u, v), -3), b);
            EXPECT_EQ(pyramid.sample(glm::vec2(u, v), pyramid.levelForFootprint(NAN)), b);
        }
}

TEST(TexturePyramid, RayConeFootprintPicksTheLevel) {
    // A 1 m x 1 m quad mapped once onto a 256 x 256 texture: 256 texels per metre.
    float scale = triangleTexelScale(glm::vec3(0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec2(0),
                                     glm::vec2(1, 0), glm::vec2(0, 1), 256, 256);
    EXPECT_NEAR(scale, 256.0f, 1e-3f);
    // A cone 1/256 m wide covers one texel; twice as far, twice as wide; seen at 60 degrees
    // from the normal the footprint stretches by 2.
    EXPECT_NEAR(rayConeFootprint(scale, 1.0f / 256.0f, 1.0f), 1.0f, 1e-5f);
    EXPECT_NEAR(rayConeFootprint(scale, 2.0f / 256.0f, 1.0f), 2.0f, 1e-5f);
    EXPECT_NEAR(rayConeFootprint(scale, 1.0f / 256.0f, 0.5f), 2.0f, 1e-5f);
    // The level is round(log2(footprint)), clamped to the pyramid (256 -> 9 levels).
    TexturePyramid pyramid(checkerboard(256, 256, 1));
    ASSERT_EQ(pyramid.levels(), 9);
    EXPECT_FLOAT_EQ(pyramid.texelScale(), 256.0f);
    for (float x = -4.03f; x <= 12.0f; x += 0.0625f) {  // off the exact half-way points
        int expected = std::clamp(int(std::floor(x + 0.5f)), 0, 8);
        EXPECT_EQ(pyramid.levelForFootprint(std::exp2(x)), expected) << "log2 footprint " << x;
    }
    EXPECT_EQ(pyramid.levelForFootprint(0.0f), 0);
    EXPECT_EQ(pyramid.levelForFootprint(-1.0f), 0);
    EXPECT_EQ(pyramid.levelForFootprint(INFINITY), 8);
    // 256 rays over the sphere: 4 pi / 256 sr each, a cone of about 0.25 rad.
    float spread = coneSpreadForRays(256);
    EXPECT_NEAR(2.0f * shading::kPi * (1.0f - std::cos(0.5f * spread)), 4.0f * shading::kPi / 256.0f, 1e-5f);
    EXPECT_NEAR(coneSpreadForRays(1), 2.0f * shading::kPi, 1e-5f);  // the whole sphere
}

TEST(TexturePyramid, ConeAlbedoAveragesDistantTexturesAndKeepsNearOnes) {
    // A textured floor quad (fine checkerboard), probe rays from above it.
    Scene scene;
    scene.textures.push_back(checkerboard(256, 256, 1));
    Material m;
    m.albedo = glm::vec3(1.0f);
    m.albedoTexture = 0;
    scene.materials.push_back(m);
    Mesh floor;
    floor.name = "floor";
    floor.positions = {{-1, 0, -1}, {1, 0, -1}, {1, 0, 1}, {-1, 0, 1}};
    floor.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    floor.indices = {0, 2, 1, 0, 3, 2};
    floor.materialIds = {0, 0};
    scene.meshes.push_back(floor);
    RayTracer tracer(scene);

    const glm::vec3 down(0, -1, 0);
    // Far away with a wide cone: the footprint spans many squares, so the average (0.5).
    RayHit far = tracer.intersect(glm::vec3(0.3f, 5.0f, 0.2f), down);
    ASSERT_TRUE(far.hit);
    EXPECT_NEAR(tracer.albedoInCone(far, down, coneSpreadForRays(256)).x, 0.5f, 0.01f);
    // The raw-hit lookup (probe rays) reads the same texels.
    for (float spread : {coneSpreadForRays(256), 1e-6f}) {
        for (glm::vec3 origin : {glm::vec3(0.3f, 5.0f, 0.2f), glm::vec3(0.3001f, 0.01f, 0.2001f)}) {
            RawHit raw;
            const TriangleSurface* surface = nullptr;
            tracer.traceFan(origin, &down, 1, &raw, &surface);
            ASSERT_TRUE(raw.hit());
            const RayHit record = tracer.intersect(origin, down);
            const glm::vec3 a = tracer.albedoInCone(raw, *surface, down, spread);
            EXPECT_NEAR(a.x, tracer.albedoInCone(record, down, spread).x, 1e-4f);
        }
    }
    // A needle-thin cone reads the texel itself, like albedoAt.
    RayHit near = tracer.intersect(glm::vec3(0.3001f, 0.01f, 0.2001f), down);
    ASSERT_TRUE(near.hit);
    EXPECT_EQ(tracer.albedoInCone(near, down, 1e-6f), tracer.albedoAt(near));
    // Untextured materials are their albedo whatever the cone.
    scene.materials[0].albedoTexture = -1;
    EXPECT_EQ(tracer.albedoInCone(far, down, 0.25f), glm::vec3(1.0f));
}
