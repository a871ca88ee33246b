// The path tracer against answers known in closed form: the white furnace (L = Le / (1 - rho),
// also truncated after B bounces), a point light and a sun over a plane, the form factor of a
// square light, glass that must not create energy, determinism across thread counts, and the
// NaN/Inf guard.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

#include <glm/gtc/matrix_transform.hpp>
#include <tbb/global_control.h>

#include "gi/pathtrace/bsdf.h"
#include "gi/pathtrace/integrator.h"
#include "gi/pathtrace/path_tracer.h"
#include "scenes/primitives.h"
#include "scenes/scene_loader.h"
#include "shaders/shared/constants.h"
#include "support/test_support.h"

using namespace voxgi;

namespace {


struct Estimate {
    double mean = 0.0;
    double standardError = 0.0;
    double meanScatterings = 0.0;
};

// Mean and standard error (from the per-sample variance) of the green beauty channel over
// `count` paths sent from `origin` in directions spread over the sphere.
Estimate estimate(const PathTracer& tracer, glm::vec3 origin, int count, bool directOnly = false) {
    double sum = 0.0, sumSq = 0.0, scatterings = 0.0;
    for (int i = 0; i < count; ++i) {
        // Fibonacci-sphere directions: every wall is seen, no sampling bias.
        float z = 1.0f - 2.0f * (float(i) + 0.5f) / float(count);
        float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
        float phi = float(i) * 2.39996323f;
        PathSample s = tracer.trace(origin, {r * std::cos(phi), r * std::sin(phi), z}, std::uint64_t(i));
        double v = directOnly ? s.direct.g : s.beauty().g;
        sum += v;
        sumSq += v * v;
        scatterings += s.scatterings;
    }
    Estimate e;
    e.mean = sum / count;
    double variance = std::max(sumSq / count - e.mean * e.mean, 0.0) * count / (count - 1);
    e.standardError = std::sqrt(variance / count);
    e.meanScatterings = scatterings / count;
    return e;
}

// The same over n paths along the one ray from `eye` through `target`.
Estimate alongRay(const PathTracer& tracer, glm::vec3 eye, glm::vec3 target, int n) {
    double sum = 0.0, sumSq = 0.0;
    for (int i = 0; i < n; ++i) {
        double v = tracer.trace(eye, target - eye, std::uint64_t(i)).beauty().g;
        sum += v;
        sumSq += v * v;
    }
    Estimate e;
    e.mean = sum / n;
    e.standardError = std::sqrt(std::max(sumSq / n - e.mean * e.mean, 0.0) / (n - 1));
    return e;
}

Scene furnace(float albedo, float emission) {
    Scene s;
    Material m;
    m.albedo = glm::vec3(albedo);
    m.emission = glm::vec3(emission);
    s.materials.push_back(m);
    s.meshes.push_back(makeBox(glm::scale(glm::mat4(1.0f), glm::vec3(2.0f)), 0, /*inwardNormals=*/true));
    s.camera.eye = glm::vec3(0.0f);
    s.camera.target = glm::vec3(0.0f, 0.0f, 1.0f);
    s.camera.width = s.camera.height = 8;
    return s;
}

}  // namespace

class WhiteFurnace : public ::testing::TestWithParam<float> {};

TEST_P(WhiteFurnace, ConvergesToEmissionOverOneMinusAlbedo) {
    const float rho = GetParam();
    Scene s = furnace(rho, 1.0f);
    PathTracer tracer(s, PathTracerOptions{});
    Estimate e = estimate(tracer, glm::vec3(0.1f, -0.2f, 0.3f), 40000);
    double expected = 1.0 / (1.0 - double(rho));
    // Truncating after B bounces loses rho^(B+1) / (1 - rho): the bounces a fixed-depth tracer
    // would need for a 1% bias. Roulette instead ends paths at random and stays unbiased.
    int bouncesFor1Percent = int(std::ceil(std::log(0.01) / std::log(double(rho)) - 1.0));
    std::printf("furnace rho=%.2f: L = %.4f +- %.4f (expected %.4f, %.2f SE), mean scatterings per path %.1f, "
                "a fixed depth needs %d bounces for 1%% bias\n",
                rho, e.mean, e.standardError, expected, std::abs(e.mean - expected) / e.standardError,
                e.meanScatterings, bouncesFor1Percent);
    EXPECT_LT(std::abs(e.mean - expected), 3.0 * e.standardError);
    EXPECT_LT(e.standardError, 0.02 * expected);  // the test has the power to see a 6% bias
}

INSTANTIATE_TEST_SUITE_P(Albedos, WhiteFurnace, ::testing::Values(0.5f, 0.9f, 0.99f));

TEST(PathTracer, FurnaceTruncatedAtMaxBounces) {
    // With at most B scattering events, L = Le (1 - rho^(B+1)) / (1 - rho).
    for (int bounces : {1, 2, 5}) {
        PathTracerOptions o;
        o.maxBounces = bounces;
        Scene s = furnace(0.8f, 1.0f);
        PathTracer tracer(s, o);
        Estimate e = estimate(tracer, glm::vec3(0.0f), 20000);
        double expected = (1.0 - std::pow(0.8, bounces + 1)) / (1.0 - 0.8);
        EXPECT_LT(std::abs(e.mean - expected), 3.0 * e.standardError + 1e-6) << "B=" << bounces << " got " << e.mean;
        if (bounces == 1) {
            // Direct AOV = emission seen + one scattering: everything when B = 1.
            Estimate d = estimate(tracer, glm::vec3(0.0f), 20000, true);
            EXPECT_NEAR(d.mean, e.mean, 1e-9);
        }
    }
}

TEST(PathTracer, PointLightOverPlaneIsIntensityCosineOverDistanceSquared) {
    Scene s = parseSceneJson(R"({
      "camera": {"eye": [0, 3, 0.001], "target": [0, 0, 0], "fov": 60, "resolution": [16, 16]},
      "materials": {"m": {"albedo": 0.5}},
      "lights": [{"type": "point", "position": [0, 1, 0], "intensity": 10}],
      "meshes": [{"type": "quad", "material": "m", "corners": [[-5,0,5],[5,0,5],[5,0,-5],[-5,0,-5]]}]})",
                             "plane.json");
    PathTracerOptions o;
    o.maxBounces = 1;
    PathTracer tracer(s, o);
    glm::vec3 eye(0.3f, 3.0f, 0.2f);
    for (glm::vec3 p : {glm::vec3(0, 0, 0), glm::vec3(0.5f, 0, 0.3f), glm::vec3(-0.8f, 0, -0.6f), glm::vec3(2, 0, 1)}) {
        float r2 = 1.0f + p.x * p.x + p.z * p.z;
        float expected = 0.5f / shading::kPi * 10.0f * (1.0f / std::sqrt(r2)) / r2;  // rho/pi * I cos / r^2
        PathSample sample = tracer.trace(eye, p - eye, 7);
        EXPECT_NEAR(sample.beauty().g, expected, 1e-4f * expected) << p.x << "," << p.z;
        EXPECT_NEAR(sample.depth, glm::length(p - eye), 1e-4f);
    }
}

TEST(PathTracer, PointLightsPastTheEarlyShadowRaysAreShadowedToo) {
    // Camera vertices trace the shadow rays of their first 64 delta lights before reading the
    // albedo and the rest after (Integrator::deltaShadows): 100 lamps of 0.1 W/sr in a row, the
    // first 60 over the plane's open half, the last 40 over a small plate that hides the origin.
    // At the origin only the first 60 count; at a point beyond the plate's shadow, all 100.
    Scene s = parseSceneJson(R"({
      "camera": {"eye": [0, 3, 0.001], "target": [0, 0, 0], "fov": 60, "resolution": [16, 16]},
      "materials": {"m": {"albedo": 0.5}},
      "meshes": [{"type": "quad", "material": "m", "corners": [[-5,0,5],[5,0,5],[5,0,-5],[-5,0,-5]]},
                 {"type": "quad", "material": "m", "corners": [[0.1,0.5,0.2],[0.7,0.5,0.2],[0.7,0.5,-0.2],[0.1,0.5,-0.2]]}]})",
                             "lamps.json");
    std::vector<glm::vec3> lamps;
    for (int i = 0; i < 100; ++i) lamps.push_back(i < 60 ? glm::vec3(-0.5f + 0.001f * float(i), 1.0f, 0.0f)
                                                         : glm::vec3(0.4f + 0.001f * float(i - 60), 1.0f, 0.0f));
    for (const glm::vec3& p : lamps) {
        Light l;
        l.type = LightType::Point;
        l.position = p;
        l.emission = glm::vec3(0.1f);
        s.lights.push_back(l);
    }
    PathTracerOptions o;
    o.maxBounces = 1;
    PathTracer tracer(s, o);
    const glm::vec3 eye(0.3f, 3.0f, 0.2f);
    auto expected = [&](glm::vec3 p, std::size_t count) {
        double sum = 0.0;
        for (std::size_t i = 0; i < count; ++i) {
            const glm::vec3 d = lamps[i] - p;
            const double r2 = double(glm::dot(d, d));
            sum += 0.5 / double(shading::kPi) * 0.1 * (double(d.y) / std::sqrt(r2)) / r2;
        }
        return sum;
    };
    const glm::vec3 hidden(0.0f, 0.0f, 0.0f), open(-2.0f, 0.0f, 1.0f);
    EXPECT_NEAR(tracer.trace(eye, hidden - eye, 7).beauty().g, expected(hidden, 60), 1e-4 * expected(hidden, 60));
    EXPECT_NEAR(tracer.trace(eye, open - eye, 7).beauty().g, expected(open, 100), 1e-4 * expected(open, 100));
}

TEST(PathTracer, SpotConeFalloffAndSun) {
    // Spot: 20 W/sr, inner 20, outer 40 degrees, pointing down from height 1 (smoothstep falloff
    // between the cone cosines, as shaders/frame/direct_light.comp). Sun: 2 W/m^2 at 60 degrees.
    Scene s = parseSceneJson(R"({
      "camera": {"eye": [0, 3, 0.001], "target": [0, 0, 0], "fov": 60, "resolution": [16, 16]},
      "materials": {"m": {"albedo": 1.0}},
      "lights": [{"type": "spot", "position": [0, 1, 0], "direction": [0, -1, 0], "intensity": 20,
                  "inner_angle": 20, "outer_angle": 40}],
      "meshes": [{"type": "quad", "material": "m", "corners": [[-5,0,5],[5,0,5],[5,0,-5],[-5,0,-5]]}]})",
                             "spot.json");
    PathTracerOptions o;
    o.maxBounces = 1;
    PathTracer tracer(s, o);
    for (float angle : {10.0f, 30.0f, 35.0f, 45.0f}) {
        float x = std::tan(glm::radians(angle));
        float cosA = std::cos(glm::radians(angle));
        float c0 = std::cos(glm::radians(40.0f)), c1 = std::cos(glm::radians(20.0f));
        float t = std::clamp((cosA - c0) / (c1 - c0), 0.0f, 1.0f);
        float falloff = t * t * (3.0f - 2.0f * t);
        float r2 = 1.0f + x * x;
        float expected = shading::kInvPi * 20.0f * falloff * cosA / r2;
        PathSample sample = tracer.trace({0.0f, 2.0f, 0.5f}, glm::vec3(x, 0, 0) - glm::vec3(0.0f, 2.0f, 0.5f), 3);
        EXPECT_NEAR(sample.beauty().r, expected, 1e-4f * expected + 1e-7f) << angle;
    }
    Scene sun = parseSceneJson(R"({
      "camera": {"eye": [0, 3, 0.001], "target": [0, 0, 0], "fov": 60, "resolution": [16, 16]},
      "materials": {"m": {"albedo": 1.0}},
      "lights": [{"type": "directional", "direction": [0.8660254, -0.5, 0], "irradiance": 2}],
      "meshes": [{"type": "quad", "material": "m", "corners": [[-5,0,5],[5,0,5],[5,0,-5],[-5,0,-5]]},
                 {"type": "box", "material": "m", "transform": {"translate": [0, 0.5, 0], "scale": 0.2}}]})",
                               "sun.json");
    PathTracer sunTracer(sun, o);
    glm::vec3 eye(0.0f, 4.0f, 0.001f);
    EXPECT_NEAR(sunTracer.trace(eye, glm::vec3(1.2f, 0, 1.2f) - eye, 1).beauty().r, 2.0f * 0.5f / shading::kPi, 1e-4f);
    glm::vec3 shadow(0.5f / std::tan(0.5235988f), 0.0f, 0.0f);
    EXPECT_EQ(sunTracer.trace(eye, shadow - eye, 1).beauty().r, 0.0f);
}

TEST(PathTracer, SquareLightFormFactor) {
    // A 1 x 1 m light of radiance 3 facing down from height h = 0.5 over a white Lambertian
    // point: L = rho * Le * F with F the differential form factor of a parallel rectangle.
    const double h = 0.5, half = 0.5, Le = 3.0, rho = 0.8;
    auto corner = [](double a, double b) {
        double x = a, y = b;
        return (x / std::sqrt(1 + x * x) * std::atan(y / std::sqrt(1 + x * x)) +
                y / std::sqrt(1 + y * y) * std::atan(x / std::sqrt(1 + y * y))) / (2.0 * shading::kPiDouble);
    };
    double F = 4.0 * corner(half / h, half / h);
    Scene s = parseSceneJson(R"({
      "camera": {"eye": [3, 0.2, 0], "target": [0, 0, 0], "fov": 60, "resolution": [16, 16]},
      "materials": {"m": {"albedo": 0.8}},
      "lights": [{"type": "quad", "corner": [-0.5, 0.5, -0.5], "edge_u": [1, 0, 0], "edge_v": [0, 0, 1], "radiance": 3}],
      "meshes": [{"type": "quad", "material": "m", "corners": [[-9,0,9],[9,0,9],[9,0,-9],[-9,0,-9]]}]})",
                             "quad.json");
    PathTracerOptions o;
    o.maxBounces = 1;
    PathTracer tracer(s, o);
    const Estimate e = alongRay(tracer, glm::vec3(3.0f, 0.2f, 0.0f), glm::vec3(0.0f), 20000);
    const double mean = e.mean, se = e.standardError;
    double expected = rho * Le * F;
    std::printf("square light: L = %.5f +- %.5f, analytic rho Le F = %.5f (F = %.5f)\n", mean, se, expected, F);
    EXPECT_LT(std::abs(mean - expected), 3.0 * se + 1e-6);
    EXPECT_LT(se, 0.01 * expected);
}

TEST(PathTracer, QuadLightOverParallelFaceAtAnyScaleAndPlace) {
    // One 0.5 x 0.5 m light facing down from h = 0.5 m over one end of an 8 x 8 m face: every
    // point of the face sees it, ever more grazing with distance, and L = rho Le F with F the
    // form factor of the parallel rectangle (sums of corner terms). The same scene scaled down
    // and moved far from the origin must give the same radiance: offsets that do not follow
    // the coordinates' magnitude either lose the far half of the face to the light's own
    // plane or lift points off their surfaces.
    const double h = 0.5, Le = 3.0, rho = 0.8;
    // Over a point at height hp below the light, in the light's plane coordinates.
    auto corner = [](double a, double b, double hp) {  // signed: odd in a and in b
        double x = a / hp, y = b / hp;
        return (x / std::sqrt(1 + x * x) * std::atan(y / std::sqrt(1 + x * x)) +
                y / std::sqrt(1 + y * y) * std::atan(x / std::sqrt(1 + y * y))) / (2.0 * shading::kPiDouble);
    };
    const double x0 = -4.0, x1 = -3.5, z0 = -0.25, z1 = 0.25;
    // From the float coordinates the scene really holds: 1 cm at 1 km is rounded by 0.6 %.
    auto formFactor = [&](glm::dvec3 p, glm::dvec3 lo, glm::dvec3 hi) {
        double hp = lo.y - p.y;
        return corner(hi.x - p.x, hi.z - p.z, hp) - corner(lo.x - p.x, hi.z - p.z, hp) -
               corner(hi.x - p.x, lo.z - p.z, hp) + corner(lo.x - p.x, lo.z - p.z, hp);
    };
    struct Placement {
        float scale, offset;
    };
    for (Placement place : {Placement{1.0f, 0.0f}, Placement{1.0f, 1000.0f}, Placement{1e-4f, 0.0f},
                            Placement{1e-4f, 1.0f}, Placement{0.1f, 1000.0f}}) {
        auto at = [&](double x, double y, double z) {
            return glm::vec3(glm::dvec3(x, y, z) * double(place.scale) + glm::dvec3(place.offset));
        };
        auto json = [&](glm::vec3 v) {
            char b[128];
            std::snprintf(b, sizeof b, "[%.9g, %.9g, %.9g]", v.x, v.y, v.z);
            return std::string(b);
        };
        Scene s = parseSceneJson(R"({
          "camera": {"eye": )" + json(at(0, 3, 3)) + R"(, "target": )" + json(at(0, 0, 0)) +
                                     R"(, "fov": 60, "resolution": [16, 16]},
          "materials": {"m": {"albedo": 0.8}},
          "lights": [{"type": "quad", "corner": )" + json(at(x0, h, z0)) + R"(, "edge_u": )" +
                                     json(at(x1 - x0, 0, 0) - at(0, 0, 0)) + R"(, "edge_v": )" +
                                     json(at(0, 0, z1 - z0) - at(0, 0, 0)) + R"(, "radiance": 3}],
          "meshes": [{"type": "quad", "material": "m", "corners": [)" +
                                     json(at(-4, 0, 4)) + "," + json(at(4, 0, 4)) + "," + json(at(4, 0, -4)) + "," +
                                     json(at(-4, 0, -4)) + "]}]}",
                                 "parallel.json");
        PathTracerOptions o;
        o.maxBounces = 1;
        PathTracer tracer(s, o);
        for (double x : {-3.75, -2.0, 0.0, 2.0, 3.9}) {
            const glm::vec3 p = at(x, 0, 0.1), eye = at(x + 0.3, 0.2, 0.6);
            const Estimate e = alongRay(tracer, eye, p, 4000);
            const double mean = e.mean, se = e.standardError;
            double expected = rho * Le * formFactor(glm::dvec3(p), glm::dvec3(at(x0, h, z0)), glm::dvec3(at(x1, h, z1)));
            EXPECT_LT(std::abs(mean - expected), 4.0 * se + 2e-3 * expected)
                << "scale " << place.scale << " offset " << place.offset << " x " << x << ": " << mean << " +- " << se
                << ", analytic " << expected;
        }
    }
}

TEST(PathTracer, LowPolySphereUnderGrazingSunMatchesTheSmoothSphere) {
    // A 12 x 6 UV sphere with interpolated normals, sun from near +x, seen from +z: its terminator
    // band (cosine to the sun below 0.3) must be as bright as the smooth sphere's,
    // rho/pi E (n.l). Dropping light below each triangle's plane, or shadow rays blocked by
    // the neighbouring facets, darken that band by several per cent.
    Scene s;
    Material m;
    m.albedo = glm::vec3(0.8f);
    s.materials.push_back(m);
    s.meshes.push_back(makeSphere(glm::mat4(1.0f), 0, 12));
    ASSERT_FALSE(s.meshes[0].normals.empty());
    Light sun;
    sun.type = LightType::Directional;
    // 7.5 degrees off the meridians of the sphere's vertices: the terminator crosses a facet that
    // faces away from the sun while part of it has normals that face it.
    const glm::vec3 toSun = glm::normalize(glm::vec3(1.0f, 0.0f, 0.1317f));
    sun.direction = -toSun;
    sun.emission = glm::vec3(2.0f);
    s.lights.push_back(sun);
    s.camera.eye = glm::vec3(0.0f, 0.0f, 4.0f);
    s.camera.width = s.camera.height = 8;
    PathTracerOptions o;
    o.maxBounces = 1;
    PathTracer tracer(s, o);
    const glm::vec3 eye = s.camera.eye;
    double rendered = 0.0, smooth = 0.0;
    int dark = 0, band = 0;
    const int grid = 200;
    for (int j = 0; j < grid; ++j)
        for (int i = 0; i < grid; ++i) {
            const glm::vec3 target(-1.0f + 2.0f * (float(i) + 0.5f) / grid, -1.0f + 2.0f * (float(j) + 0.5f) / grid, 0.0f);
            const glm::vec3 d = glm::normalize(target - eye);
            const PathSample p = tracer.trace(eye, d, std::uint64_t(j * grid + i));
            if (p.depth <= 0.0f) continue;
            const float cosine = glm::dot(glm::normalize(eye + p.depth * d), toSun);
            if (!(cosine > 0.0f && cosine < 0.3f)) continue;
            ++band;
            rendered += p.direct.g;
            smooth += 0.8 / shading::kPiDouble * 2.0 * double(cosine);
            if (p.direct.g <= 0.0f) ++dark;
        }
    std::printf("terminator band: %d hits, %d black, rendered / smooth sphere = %.4f\n", band, dark, rendered / smooth);
    ASSERT_GT(band, 1000);
    EXPECT_NEAR(rendered / smooth, 1.0, 0.02);
    EXPECT_LT(dark, band / 100);
}

TEST(PathTracer, GlossyUnderSquareLightMatchesQuadrature) {
    // Light sampling, BSDF sampling and their MIS weights must add up to the integral of the
    // BRDF over the light, L = Le * integral f cos cos' / r^2 dA, here by a 400x400 midpoint rule.
    struct Case {
        const char* material;
        float albedo, roughness, metallic, specular;
    };
    for (const Case& k : {Case{"metal", 0.9f, 0.4f, 1.0f, 0.0f}, Case{"coated", 0.5f, 0.25f, 0.0f, 0.5f}}) {
        char json[1024];
        std::snprintf(json, sizeof json, R"({
          "camera": {"eye": [-1.5, 0.8, 0.2], "target": [0, 0, 0], "fov": 60, "resolution": [16, 16]},
          "materials": {"m": {"albedo": %g, "roughness": %g, "metallic": %g, "specular": %g}},
          "lights": [{"type": "quad", "corner": [-0.2, 0.5, -0.5], "edge_u": [1, 0, 0], "edge_v": [0, 0, 1], "radiance": 2}],
          "meshes": [{"type": "quad", "material": "m", "corners": [[-9,0,9],[9,0,9],[9,0,-9],[-9,0,-9]]}]})",
                      k.albedo, k.roughness, k.metallic, k.specular);
        Scene s = parseSceneJson(json, "glossy.json");
        PathTracerOptions o;
        o.maxBounces = 1;
        PathTracer tracer(s, o);
        const glm::vec3 eye(-1.5f, 0.8f, 0.2f), p(0.0f);
        pt::Bsdf bsdf(s.materials[0], s.materials[0].albedo, glm::normalize(eye - p), {0, 1, 0}, {0, 1, 0}, true);
        const int grid = 400;
        double integral = 0.0;
        for (int i = 0; i < grid; ++i)
            for (int j = 0; j < grid; ++j) {
                glm::vec3 q(-0.2f + (float(i) + 0.5f) / grid, 0.5f, -0.5f + (float(j) + 0.5f) / grid);
                glm::vec3 d = q - p;
                float r2 = glm::dot(d, d);
                glm::vec3 wi = d / std::sqrt(r2);
                // eval includes cos at the surface; the light faces down: cos' = wi.y.
                integral += double(bsdf.eval(wi).g) * double(wi.y) / double(r2) / double(grid * grid);
            }
        double expected = 2.0 * integral;
        const Estimate e = alongRay(tracer, eye, p, 20000);
        const double mean = e.mean, se = e.standardError;
        std::printf("%s under a square light: L = %.5f +- %.5f, quadrature %.5f\n", k.material, mean, se, expected);
        EXPECT_LT(std::abs(mean - expected), 3.0 * se + 1e-4 * expected) << k.material;
        EXPECT_LT(se, 0.02 * expected) << k.material;
    }
}

TEST(PathTracer, ABsdfSeenFromAnotherDirectionIsTheOneBuiltFromIt) {
    // Light subpaths sample with the BSDF seen from the light, and MIS needs reverse pdfs: both
    // come from Bsdf::seenFrom, which must turn normals and indices over exactly when the new
    // direction lies on the other side.
    Material plastic;
    plastic.albedo = glm::vec3(0.6f, 0.5f, 0.4f);
    plastic.roughness = 0.5f;
    plastic.specular = 0.04f;
    Material roughGlass = plastic;
    roughGlass.transmission = 0.8f;
    roughGlass.ior = 1.5f;
    const glm::vec3 geometric(0.0f, 1.0f, 0.0f), shading = glm::normalize(glm::vec3(0.2f, 1.0f, 0.1f));
    const glm::vec3 views[] = {glm::normalize(glm::vec3(0.3f, 0.8f, -0.2f)), glm::normalize(glm::vec3(-0.6f, 0.3f, 0.5f)),
                               glm::normalize(glm::vec3(0.1f, -0.9f, 0.3f))};
    for (const Material& m : {plastic, roughGlass})
        for (const glm::vec3& from : views)
            for (const glm::vec3& to : views) {
                const pt::Bsdf first(m, m.albedo, from, geometric, shading, glm::dot(geometric, from) > 0.0f);
                const pt::Bsdf seen = first.seenFrom(to);
                const pt::Bsdf built(m, m.albedo, to, geometric, shading, glm::dot(geometric, to) > 0.0f);
                for (const glm::vec3& wi : views) {
                    float pdfSeen, pdfBuilt;
                    const glm::vec3 fSeen = seen.evalPdf(wi, &pdfSeen), fBuilt = built.evalPdf(wi, &pdfBuilt);
                    EXPECT_FLOAT_EQ(pdfSeen, pdfBuilt) << m.transmission;
                    EXPECT_FLOAT_EQ(fSeen.g, fBuilt.g) << m.transmission;
                }
            }
}

TEST(PathTracer, ABsdfGivenItsAlbedoLaterIsTheSameAndMayReflectCoversEveryNonZeroValue) {
    // The camera path builds its BSDF before the albedo's texels arrive, traces the delta
    // lights' shadow rays where mayReflect says light can be reflected, then sets the albedo:
    // the BSDF must equal the one built with it, and no direction with a non-zero value may be
    // left untraced, for any albedo (black included: its specular lobe still reflects).
    Material plastic;
    plastic.roughness = 0.5f;
    plastic.specular = 0.04f;
    Material metal = plastic;
    metal.metallic = 1.0f;
    metal.roughness = 0.2f;
    Material roughGlass = plastic;
    roughGlass.transmission = 0.8f;
    roughGlass.ior = 1.5f;
    Material clearGlass = roughGlass;
    clearGlass.roughness = 0.0f;
    Material matte;
    matte.specular = 0.0f;
    const glm::vec3 geometric(0.0f, 1.0f, 0.0f), shading = glm::normalize(glm::vec3(0.3f, 1.0f, 0.1f));
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    auto direction = [&] { return glm::normalize(glm::vec3(u(rng), u(rng), u(rng))); };
    int nonZero = 0, skipped = 0;
    for (const Material& m : {plastic, metal, roughGlass, clearGlass, matte})
        for (const glm::vec3 albedo : {glm::vec3(0.6f, 0.5f, 0.4f), glm::vec3(0.0f), glm::vec3(1.0f)})
            for (int view = 0; view < 20; ++view) {
                const glm::vec3 wo = direction();
                const bool front = glm::dot(geometric, wo) > 0.0f;
                const pt::Bsdf built(m, albedo, wo, geometric, shading, front);
                pt::Bsdf later(m, wo, geometric, shading, front);
                const pt::Bsdf frame = later;
                later.setAlbedo(m, albedo);
                for (int light = 0; light < 50; ++light) {
                    const glm::vec3 wi = direction();
                    float pdfBuilt, pdfLater;
                    const glm::vec3 fBuilt = built.evalPdf(wi, &pdfBuilt), fLater = later.evalPdf(wi, &pdfLater);
                    EXPECT_EQ(pdfBuilt, pdfLater);
                    EXPECT_EQ(fBuilt, fLater);
                    const bool reflects = fBuilt.r + fBuilt.g + fBuilt.b > 0.0f;
                    nonZero += reflects ? 1 : 0;
                    skipped += frame.mayReflect(wi) ? 0 : 1;
                    EXPECT_TRUE(!reflects || frame.mayReflect(wi)) << m.metallic << " " << m.transmission;
                }
            }
    // Both cases occur: the test would pass vacuously if every direction were traced or none reflected.
    EXPECT_GT(nonZero, 1000);
    EXPECT_GT(skipped, 1000);
}

TEST(PathTracer, GlassDoesNotCreateEnergy) {
    // Walls that emit 1 and absorb everything; a clear or rough glass sphere in the middle can
    // only redirect light, so every direction sees at most 1 (exactly 1 for smooth glass).
    for (float roughness : {0.0f, 0.3f}) {
        Scene s = furnace(0.0f, 1.0f);
        Material glass;
        glass.albedo = glm::vec3(1.0f);
        glass.transmission = 1.0f;
        glass.ior = 1.5f;
        glass.roughness = roughness;
        s.materials.push_back(glass);
        s.meshes.push_back(makeSphere(glm::scale(glm::mat4(1.0f), glm::vec3(0.6f)), 1, 48));
        PathTracer tracer(s, PathTracerOptions{});
        // Look at the sphere from a corner of the box so most paths go through the glass.
        glm::vec3 eye(0.0f, 0.0f, -0.9f);
        double sum = 0.0, sumSq = 0.0;
        const int n = 20000;
        for (int i = 0; i < n; ++i) {
            float a = 0.5f * float(i % 100) / 100.0f - 0.25f, b = 0.5f * float(i / 100) / 200.0f - 0.25f;
            double v = tracer.trace(eye, {a, b, 1.0f}, std::uint64_t(i)).beauty().g;
            sum += v;
            sumSq += v * v;
        }
        double mean = sum / n, se = std::sqrt(std::max(sumSq / n - mean * mean, 0.0) / (n - 1));
        std::printf("glass roughness %.1f: L = %.4f +- %.4f (at most 1)\n", roughness, mean, se);
        if (roughness == 0.0f) {
            // Reflection and refraction weights are exact (roulette leaves lossless paths alone),
            // so the answer is 1 up to float rounding of the eta^2 factors.
            EXPECT_NEAR(mean, 1.0, 1e-5);
        } else {
            // Single-scattering microfacets lose a little energy, and must not gain any.
            EXPECT_LT(mean, 1.0 + 3.0 * se);
            EXPECT_GT(mean, 0.9);
        }
    }
}

// A mirror floor, a quad light facing it and a white ceiling above the light: the ceiling
// gets light only by way of the mirror (a caustic). `ceilingMaterial` lets a test make it glossy.
Scene mirrorUnderCeiling(const char* ceilingMaterial = R"({"albedo": 0.8, "specular": 0})") {
    char json[1400];
    std::snprintf(json, sizeof json, R"({
      "camera": {"eye": [3, 0.8, 0], "target": [2, 1, 0], "fov": 40, "resolution": [16, 16]},
      "materials": {"mirror": {"albedo": 0.9, "metallic": 1, "roughness": 0},
                    "ceiling": %s},
      "lights": [{"type": "quad", "corner": [-0.5, 0.5, -0.5], "edge_u": [1, 0, 0], "edge_v": [0, 0, 1], "radiance": 3}],
      "meshes": [{"type": "quad", "material": "mirror", "corners": [[-9,0,9],[9,0,9],[9,0,-9],[-9,0,-9]]},
                 {"type": "quad", "material": "ceiling", "corners": [[-9,1,-9],[9,1,-9],[9,1,9],[-9,1,9]]}]})",
                  ceilingMaterial);
    return parseSceneJson(json, "mirror.json");
}

// `samples` per pixel of `scene` with caustics and without (light subpaths off in both: without
// caustics none are traced), the same options otherwise.
std::pair<Image, Image> withAndWithoutCaustics(const Scene& scene, PathTracerOptions options, int samples) {
    options.lightPaths = false;
    PathTracer with(scene, options);
    with.render(samples);
    options.caustics = false;
    PathTracer without(scene, options);
    without.render(samples);
    return {with.image(), without.image()};
}

TEST(PathTracer, WithoutCausticsACeilingLitOnlyThroughAMirrorGetsNothing) {
    // The light faces down, so the ceiling point (2, 1, 0) sees it only in the mirror.
    Scene s = mirrorUnderCeiling();
    const glm::vec3 eye(3.0f, 0.8f, 0.0f), p(2.0f, 1.0f, 0.0f);
    PathTracerOptions o;
    PathTracer with(s, o);
    const Estimate caustic = alongRay(with, eye, p, 4000);
    o.caustics = false;
    PathTracer without(s, o);
    const Estimate none = alongRay(without, eye, p, 4000);
    std::printf("ceiling lit through a mirror: %.5f +- %.5f with caustics, %.5f without\n", caustic.mean,
                caustic.standardError, none.mean);
    EXPECT_GT(caustic.mean, 10.0 * caustic.standardError);
    EXPECT_EQ(none.mean, 0.0);
    // A glossy ceiling keeps only its diffuse lobe past the first surface too: still nothing.
    Scene glossy = mirrorUnderCeiling(R"({"albedo": 0.8, "specular": 0.5, "roughness": 0.3})");
    PathTracer glossyWithout(glossy, o);
    EXPECT_EQ(alongRay(glossyWithout, eye, p, 1000).mean, 0.0);
}

TEST(PathTracer, WithoutCausticsWhatTheCameraSeesInAMirrorAndDiffuseLightStayTheSame) {
    // Up to two scatterings, a camera that sees only a mirror wall sees in it the floor lit by
    // the light above and the light itself: no caustic, so the image must come out bit for bit
    // as with caustics (light subpaths off in both: without caustics none are traced).
    Scene s = parseSceneJson(R"({
      "camera": {"eye": [-0.5, 0.25, 0], "target": [-1, 0.25, 0], "fov": 40, "resolution": [16, 16]},
      "materials": {"mirror": {"albedo": 0.9, "metallic": 1, "roughness": 0}, "floor": {"albedo": 0.8}},
      "lights": [{"type": "quad", "corner": [-0.5, 0.5, -0.5], "edge_u": [1, 0, 0], "edge_v": [0, 0, 1], "radiance": 3}],
      "meshes": [{"type": "quad", "material": "floor", "corners": [[-9,0,9],[9,0,9],[9,0,-9],[-9,0,-9]]},
                 {"type": "quad", "material": "mirror", "corners": [[-1,0,-2],[-1,0,2],[-1,2,2],[-1,2,-2]]}]})",
                             "mirror-wall.json");
    PathTracerOptions o;
    o.maxBounces = 2;
    const auto [with, without] = withAndWithoutCaustics(s, o, 4);
    EXPECT_EQ(with.find("beauty")->data, without.find("beauty")->data);
    // The lit floor in the mirror: light after two scatterings, the indirect layer.
    const std::vector<float>& floor = with.find("indirect")->data;
    EXPECT_GT(*std::max_element(floor.begin(), floor.end()), 0.05f);
    // And a diffuse Cornell box at any depth.
    Scene box = test::cornellBox();
    for (Material& m : box.materials) m.specular = 0.0f;
    PathTracerOptions b;
    b.width = b.height = 24;
    const auto [boxWith, boxWithout] = withAndWithoutCaustics(box, b, 2);
    EXPECT_EQ(boxWith.find("beauty")->data, boxWithout.find("beauty")->data);
    double sum = 0.0;
    for (float v : boxWith.find("indirect")->data) sum += v;
    EXPECT_GT(sum, 0.0);
}

TEST(PathTracer, SameImageWhateverTheThreadCount) {
    Scene s = test::cornellBox();
    PathTracerOptions o;
    o.width = o.height = 40;
    o.seed = 11;
    Image one, two;
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
        PathTracer t(s, o);
        t.render(3);
        one = t.image();
    }
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
        PathTracer t(s, o);
        t.render(1);
        t.render(2);  // progressive passes give the same samples as one pass
        two = t.image();
    }
    for (const char* layer : {"beauty", "direct", "indirect", "albedo", "normal", "depth"}) {
        ASSERT_NE(one.find(layer), nullptr) << layer;
        EXPECT_EQ(one.find(layer)->data, two.find(layer)->data) << layer;
    }
    // And another seed gives another image.
    o.seed = 12;
    PathTracer other(s, o);
    other.render(3);
    EXPECT_NE(other.image().find("beauty")->data, one.find("beauty")->data);
}

TEST(PathTracer, PathsTracedTogetherAreThePathsTracedAlone) {
    // Integrator::traceBatch interleaves the stages of many paths' bounces; each path must still
    // be the one trace() makes alone, bit for bit. The Cornell box with a point light (so light
    // subpaths and connections run), a sun with a disc and a glass block (delta lobes).
    Scene s = test::cornellBox();
    Light lamp;
    lamp.type = LightType::Point;
    lamp.position = glm::vec3(0.3f, 0.45f, 0.3f);
    lamp.emission = glm::vec3(0.05f);
    s.lights.push_back(lamp);
    Light sun;
    sun.type = LightType::Directional;
    sun.direction = glm::normalize(glm::vec3(0.1f, -0.3f, 1.0f));  // in through the open front
    sun.emission = glm::vec3(2.0f);
    sun.angularDiameterDegrees = 2.0f;
    s.lights.push_back(sun);
    Material glass;
    glass.transmission = 1.0f;
    glass.roughness = 0.0f;
    s.materials.push_back(glass);
    s.meshes.push_back(makeBox(glm::translate(glm::mat4(1.0f), glm::vec3(0.2f, 0.1f, 0.25f)) *
                                   glm::scale(glm::mat4(1.0f), glm::vec3(0.05f)),
                               std::uint32_t(s.materials.size() - 1), false));
    s.addQuadLightGeometry();
    const RayTracer tracer(s);
    const pt::Integrator integrator(s, tracer, 0);
    ASSERT_TRUE(integrator.tracesLightPaths());
    pt::LightVertices pool;
    for (std::uint64_t j = 0; j < 64; ++j) {
        pool.rays += integrator.traceLightPath(pt::PathSampler(5, 1000 + j, 0), pool.vertices);
        ++pool.paths;
    }
    ASSERT_FALSE(pool.vertices.empty());
    const glm::vec3 eye = s.camera.eye;
    constexpr int kPaths = 37;  // not a multiple of anything the batch might assume
    std::vector<RayHit> firstHits;
    std::vector<pt::Integrator::PathStart> starts;
    firstHits.reserve(kPaths);
    for (int i = 0; i < kPaths; ++i) {
        const glm::vec3 d = glm::normalize(glm::vec3(0.05f * float(i % 7) - 0.15f, 0.06f * float(i / 7) - 0.15f, 1.0f));
        firstHits.push_back(tracer.intersect(eye, d));
        // Every other path is given its first hit, as the tiles do.
        starts.push_back({eye, d, pt::PathSampler(5, std::uint64_t(i), 3), i % 2 ? &firstHits.back() : nullptr});
    }
    const pt::LightVertices* pools[] = {nullptr, &pool};
    for (const pt::LightVertices* lightVertices : pools) {
        std::vector<PathSample> together(kPaths);
        integrator.traceBatch(starts.data(), kPaths, lightVertices, together.data());
        int scattered = 0;
        for (int i = 0; i < kPaths; ++i) {
            const pt::Integrator::PathStart& start = starts[std::size_t(i)];
            const PathSample alone = integrator.trace(start.origin, start.direction, start.sampler, lightVertices);
            const PathSample& t = together[std::size_t(i)];
            EXPECT_EQ(t.direct, alone.direct) << "path " << i;
            EXPECT_EQ(t.indirect, alone.indirect) << "path " << i;
            EXPECT_EQ(t.albedo, alone.albedo) << "path " << i;
            EXPECT_EQ(t.normal, alone.normal) << "path " << i;
            EXPECT_EQ(t.depth, alone.depth) << "path " << i;
            EXPECT_EQ(t.rays, alone.rays) << "path " << i;
            EXPECT_EQ(t.scatterings, alone.scatterings) << "path " << i;
            scattered += alone.scatterings >= 2;
        }
        EXPECT_GT(scattered, kPaths / 4);  // the batch ran paths of several bounces
    }
}

TEST(PathTracer, AovsAddUpAndBackgroundIsEmpty) {
    Scene s = test::cornellBox();
    PathTracerOptions o;
    o.width = o.height = 24;
    PathTracer t(s, o);
    t.render(4);
    Image img = t.image();
    const auto& b = img.find("beauty")->data;
    const auto& d = img.find("direct")->data;
    const auto& i = img.find("indirect")->data;
    for (std::size_t k = 0; k < b.size(); ++k) {
        ASSERT_NEAR(b[k], d[k] + i[k], 1e-5f * (1.0f + b[k]));
        ASSERT_GE(i[k], 0.0f);
    }
    // The open front of the box shows the empty background in the corners? The Cornell box
    // camera sees walls everywhere, so depth is positive in the centre pixel.
    EXPECT_GT(img.find("depth")->data[12 * 24 + 12], 0.5f);
    EXPECT_EQ(t.droppedSamples(), 0u);
}

TEST(PathTracer, NanAndInfSamplesAreDroppedAndCounted) {
    // An intensity near the float maximum overflows to infinity over 1/r^2 at r < 1.
    Scene s = parseSceneJson(R"({
      "camera": {"eye": [0, 3, 0.001], "target": [0, 0, 0], "fov": 60, "resolution": [8, 8]},
      "materials": {"m": {"albedo": 0.5}},
      "lights": [{"type": "point", "position": [0, 0.5, 0], "intensity": 3e38}],
      "meshes": [{"type": "quad", "material": "m", "corners": [[-5,0,5],[5,0,5],[5,0,-5],[-5,0,-5]]}]})",
                             "inf.json");
    PathTracer t(s, PathTracerOptions{});
    t.render(2);
    EXPECT_GT(t.droppedSamples(), 0u);
    const Image image = t.image();  // a copy: iterating the temporary's layers would dangle
    for (const ImageLayer& layer : image.layers())
        for (float v : layer.data) ASSERT_TRUE(std::isfinite(v)) << layer.name;
}

TEST(PathTracer, ReferenceCommandWritesLayers) {
    std::string dir = test::makeTempDir("pt_cli");
    auto r = test::runVoxgi("reference cornell-box --spp 2 --width 16 --height 16 --seed 3 -o " + dir + "/ref.exr --quiet");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("rays/s"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("2 spp"), std::string::npos) << r.output;
    Image img = readExr(dir + "/ref.exr");
    EXPECT_EQ(img.width(), 16);
    for (const char* layer : {"beauty", "direct", "indirect", "albedo", "normal", "depth"})
        EXPECT_NE(img.find(layer), nullptr) << layer;
    EXPECT_EQ(img.find("depth")->channels, 1);
    // Bad input: one-line error, exit 2, nothing written.
    auto bad = test::runVoxgi("reference cornell-box --spp 0 -o " + dir + "/bad.exr");
    EXPECT_EQ(bad.exitCode, 2) << bad.output;
    auto both = test::runVoxgi("reference cornell-box --spp 2 --time 1 -o " + dir + "/bad.exr");
    EXPECT_EQ(both.exitCode, 2) << both.output;
    EXPECT_FALSE(test::fileExists(dir + "/bad.exr"));
    auto timed = test::runVoxgi("reference cornell-box --time 0.2 --width 16 --height 16 -o " + dir + "/t.exr --quiet");
    EXPECT_EQ(timed.exitCode, 0) << timed.output;
}
