// The shared light model and G-buffer encoding (shaders/shared/) compiled as C++ and as GLSL
// give the same numbers: every light kind evaluated at the same points in both languages, and
// the G-buffer round trip and diffuse albedo likewise. Plus the model's own analytic values.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "gl/program.h"
#include "gl/resources.h"
#include "scenes/scene.h"
#include "shaders/shared/constants.h"
#include "shaders/shared/gbuffer.h"
#include "shaders/shared/light_model.h"
#include "support/test_support.h"

using namespace voxgi;

namespace {

constexpr float kRelative = 1e-5f;

Light pointLight() {
    Light l;
    l.type = LightType::Point;
    l.position = {0.3f, 2.0f, -0.4f};
    l.emission = {5.0f, 3.0f, 1.0f};
    return l;
}

Light spotLight(float inner, float outer) {
    Light l;
    l.type = LightType::Spot;
    l.position = {0.1f, 3.0f, 0.2f};
    l.direction = {0.2f, -1.0f, 0.1f};  // not unit: packing normalizes it
    l.innerConeDegrees = inner;
    l.outerConeDegrees = outer;
    l.emission = {40.0f, 30.0f, 20.0f};
    return l;
}

Light sunLight() {
    Light l;
    l.type = LightType::Directional;
    l.direction = {0.3f, -1.0f, 0.2f};
    l.emission = {3.0f, 2.5f, 2.0f};
    return l;
}

// A sun with a wide disc (the real sun's is 0.53 degrees), so that its directions differ measurably.
Light discSunLight() {
    Light l = sunLight();
    l.angularDiameterDegrees = 8.0f;
    return l;
}

Light quadLight(glm::vec3 corner, glm::vec3 edgeU, glm::vec3 edgeV) {
    Light l;
    l.type = LightType::Quad;
    l.position = corner;
    l.edgeU = edgeU;
    l.edgeV = edgeV;
    l.emission = {10.0f, 8.0f, 6.0f};
    return l;
}

std::vector<Light> testLights() {
    return {pointLight(),
            spotLight(20.0f, 35.0f),
            spotLight(25.0f, 25.0f),  // no soft band: a hard edge
            sunLight(),
            discSunLight(),
            quadLight({-0.5f, 2.5f, -0.5f}, {1.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 1.0f}),   // facing down
            quadLight({1.0f, 0.5f, -1.0f}, {0.0f, 0.6f, 0.3f}, {0.2f, 0.0f, 0.9f})};  // tilted
}

// A unit vector at `angle` radians from unit `axis`, turned by `turn` about it.
glm::vec3 offAxis(glm::vec3 axis, float angle, float turn) {
    glm::vec3 t = glm::normalize(glm::cross(axis, std::abs(axis.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0)));
    glm::vec3 b = glm::cross(axis, t);
    return std::cos(angle) * axis + std::sin(angle) * (std::cos(turn) * t + std::sin(turn) * b);
}

struct Query {
    glm::vec3 point;
    int light;
    glm::vec2 sample;
};

// Random points in a box around the lights, and for each light the points that test its
// shape: inside, between and outside a spot's cones and on its soft edge (kept off a hard
// edge, where one ulp of cosine decides all or nothing); in front of, behind and in the plane
// of a quad.
std::vector<Query> testQueries(const std::vector<Light>& lights) {
    std::mt19937 rng(20240611);
    std::uniform_real_distribution<float> box(-3.0f, 3.0f), unit(0.0f, 1.0f), spread(0.2f, 4.0f);
    std::vector<Query> queries;
    auto sample = [&] { return glm::vec2(unit(rng), unit(rng)) * 0.999f; };
    for (int i = 0; i < 300; ++i) {
        const glm::vec3 p(box(rng), box(rng), box(rng));
        for (int l = 0; l < int(lights.size()); ++l) queries.push_back({p, l, sample()});
    }
    for (int l = 0; l < int(lights.size()); ++l) {
        const Light& light = lights[std::size_t(l)];
        if (light.type == LightType::Spot) {
            const glm::vec3 axis = glm::normalize(light.direction);
            const float inner = glm::radians(light.innerConeDegrees), outer = glm::radians(light.outerConeDegrees);
            std::vector<float> angles = {0.0f, 0.5f * inner, outer + 0.01f, 1.2f, 2.5f};
            if (light.innerConeDegrees < light.outerConeDegrees)
                angles.insert(angles.end(), {inner, 0.5f * (inner + outer), outer});
            else angles.push_back(outer - 0.01f);
            for (float angle : angles)
                for (int k = 0; k < 8; ++k)
                    queries.push_back({light.position + spread(rng) * offAxis(axis, angle, 0.8f * float(k)), l,
                                       sample()});
        }
        if (light.type == LightType::Quad) {
            const glm::vec3 n = light.quadNormal(), c = light.quadCenter();
            for (int k = 0; k < 40; ++k) {
                const glm::vec3 along = (unit(rng) - 0.5f) * light.edgeU + (unit(rng) - 0.5f) * light.edgeV;
                const float h = spread(rng);
                queries.push_back({c + along + h * n, l, sample()});        // in front
                queries.push_back({c + along - h * n, l, sample()});        // behind
                queries.push_back({c + 3.0f * along + 1e-3f * n, l, sample()});  // grazing, beside it
            }
        }
    }
    return queries;
}

// The strength the light would have at this distance without its angular factor (spot cone,
// quad cosine): near a cone's edge or a quad's plane the factor is a difference of nearly equal
// cosines, whose relative error one ulp of either language's dot product makes unbounded.
float fullStrength(const Light& light, const shading::IncidentLight& c) {
    const float e = glm::length(light.emission);
    if (light.type == LightType::Directional) return e;
    const float d2 = c.distance * c.distance;
    return light.type == LightType::Quad ? e * light.area() / d2 : e / d2;
}

bool close(float a, float b, float scale) {
    if (a == b) return true;  // infinities included
    if (!std::isfinite(a) || !std::isfinite(b)) return false;
    return std::abs(a - b) <= kRelative * std::max({std::abs(a), std::abs(b), scale});
}

}  // namespace

TEST(LightModel, AnalyticValues) {
    using shading::evaluateLight;
    using shading::packLight;
    const glm::vec2 centre(0.5f);

    const Light point = pointLight();
    const glm::vec3 p = point.position + glm::vec3(0.0f, -2.0f, 0.0f);
    shading::IncidentLight i = evaluateLight(packLight(point), p, centre);
    EXPECT_FLOAT_EQ(i.distance, 2.0f);
    EXPECT_FLOAT_EQ(i.direction.y, 1.0f);
    EXPECT_FLOAT_EQ(i.irradiance.x, 5.0f / 4.0f);
    EXPECT_FLOAT_EQ(i.falloff, 0.25f);
    EXPECT_EQ(evaluateLight(packLight(point), point.position, centre).falloff, 0.0f);  // at the light

    const Light spot = spotLight(20.0f, 35.0f);
    const glm::vec3 axis = glm::normalize(spot.direction);
    EXPECT_FLOAT_EQ(evaluateLight(packLight(spot), spot.position + 2.0f * axis, centre).irradiance.x, 40.0f / 4.0f);
    EXPECT_EQ(evaluateLight(packLight(spot), spot.position + 2.0f * offAxis(axis, 0.7f, 0.0f), centre).falloff, 0.0f);
    // Half way through the soft band, at unit distance: smoothstep between the cone cosines.
    const double t = (std::cos(glm::radians(27.5)) - std::cos(glm::radians(35.0))) /
                     (std::cos(glm::radians(20.0)) - std::cos(glm::radians(35.0)));
    const glm::vec3 inBand = spot.position + offAxis(axis, glm::radians(27.5f), 1.0f);
    EXPECT_NEAR(evaluateLight(packLight(spot), inBand, centre).falloff, t * t * (3.0 - 2.0 * t), 1e-5);
    // A hard edge at the outer angle, falloff 1 / d^2 inside (unit distance here), 0 outside.
    const shading::PackedLight hard = packLight(spotLight(25.0f, 25.0f));
    const glm::vec3 apex = spot.position;
    EXPECT_FLOAT_EQ(evaluateLight(hard, apex + offAxis(axis, glm::radians(24.0f), 0.0f), centre).falloff, 1.0f);
    EXPECT_EQ(evaluateLight(hard, apex + offAxis(axis, glm::radians(26.0f), 0.0f), centre).falloff, 0.0f);

    const Light sun = sunLight();
    i = evaluateLight(packLight(sun), glm::vec3(1.0f), centre);
    EXPECT_TRUE(std::isinf(i.distance) && i.distance > 0.0f);
    EXPECT_EQ(i.irradiance, sun.emission);
    EXPECT_NEAR(glm::dot(i.direction, -glm::normalize(sun.direction)), 1.0f, 1e-6f);

    // Quad: L A cos(theta) / d^2 from the sample point, nothing behind it.
    const Light quad = quadLight({-0.5f, 2.5f, -0.5f}, {1.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 1.0f});
    const glm::vec3 q = quad.position + 0.25f * quad.edgeU + 0.75f * quad.edgeV;
    const glm::vec3 below = q + glm::vec3(1.0f, -2.0f, 0.0f);
    i = evaluateLight(packLight(quad), below, glm::vec2(0.25f, 0.75f));
    const float d2 = 5.0f, cosine = 2.0f / std::sqrt(5.0f);
    EXPECT_NEAR(i.irradiance.x, 10.0f * 1.0f * cosine / d2, 1e-5f);
    EXPECT_NEAR(i.distance, std::sqrt(d2), 1e-6f);
    EXPECT_EQ(evaluateLight(packLight(quad), q + glm::vec3(0.0f, 1.0f, 0.0f), glm::vec2(0.25f, 0.75f)).falloff, 0.0f);
}

TEST(LightModel, SunDiscDirectionsFillTheConeEvenly) {
    const Light sun = discSunLight();
    const shading::PackedLight packed = shading::packLight(sun);
    const glm::vec3 axis = -glm::normalize(sun.direction);
    const double alpha = glm::radians(0.5 * double(sun.angularDiameterDegrees));
    EXPECT_NEAR(double(packed.shape.w), 1.0 - std::cos(alpha), 1e-7);
    EXPECT_EQ(shading::packLight(sunLight()).shape.w, 0.0f);  // no disc: one direction
    // u.x = 0 is the axis.
    EXPECT_NEAR(glm::dot(shading::evaluateLight(packed, glm::vec3(0.0f), glm::vec2(0.0f, 0.3f)).direction, axis), 1.0f, 1e-6f);
    // Over a grid of u: every direction inside the cone, their mean on the axis, and half of them
    // inside the cone of half the solid angle (uniform in solid angle).
    const int n = 64;
    glm::dvec3 sum(0.0);
    int inner = 0;
    const double halfCos = 1.0 - 0.5 * (1.0 - std::cos(alpha));
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const glm::vec2 u((float(i) + 0.5f) / float(n), (float(j) + 0.5f) / float(n));
            const shading::IncidentLight incident = shading::evaluateLight(packed, glm::vec3(0.0f), u);
            EXPECT_EQ(incident.irradiance, sun.emission);
            const double c = glm::dot(glm::dvec3(incident.direction), glm::dvec3(axis));
            EXPECT_GE(c, std::cos(alpha) - 1e-6);
            inner += c > halfCos ? 1 : 0;
            sum += glm::dvec3(incident.direction);
        }
    const glm::dvec3 mean = sum / double(n * n);
    EXPECT_NEAR(glm::length(glm::cross(mean, glm::dvec3(axis))), 0.0, 1e-4);
    EXPECT_NEAR(double(inner) / double(n * n), 0.5, 0.02);
}

TEST(LightModel, GlslAgreesWithCpp) {
    test::useHeadlessContext();
    const std::vector<Light> lights = testLights();
    std::vector<shading::PackedLight> packed;
    for (const Light& l : lights) packed.push_back(shading::packLight(l));
    const std::vector<Query> queries = testQueries(lights);
    std::vector<glm::vec4> in;
    for (const Query& q : queries) {
        in.push_back(glm::vec4(q.point, float(q.light)));
        in.push_back(glm::vec4(q.sample, 0.0f, 0.0f));
    }
    gl::Handle lightBuffer = gl::createBuffer(packed.size() * sizeof(shading::PackedLight), packed.data(), 0);
    gl::Handle queryBuffer = gl::createBuffer(in.size() * sizeof(glm::vec4), in.data(), 0);
    gl::Handle resultBuffer = gl::createBuffer(in.size() * sizeof(glm::vec4), nullptr, GL_DYNAMIC_STORAGE_BIT);
    gl::Program program = gl::Program::compute("tests/light_model.comp");
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, lightBuffer.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, queryBuffer.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, resultBuffer.id());
    program.use();
    program.set("uCount", int(queries.size()));
    glDispatchCompute(GLuint((queries.size() + 63) / 64), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<glm::vec4> gpu(in.size());
    glGetNamedBufferSubData(resultBuffer.id(), 0, GLsizeiptr(gpu.size() * sizeof(glm::vec4)), gpu.data());

    int lit = 0, dark = 0, partial = 0;
    for (std::size_t i = 0; i < queries.size(); ++i) {
        const Query& q = queries[i];
        const Light& light = lights[std::size_t(q.light)];
        const shading::IncidentLight c = shading::evaluateLight(packed[std::size_t(q.light)], q.point, q.sample);
        const glm::vec4 g0 = gpu[2 * i], g1 = gpu[2 * i + 1];
        const float strength = fullStrength(light, c);
        SCOPED_TRACE(testing::Message() << "query " << i << ", light " << q.light << " at (" << q.point.x << ", "
                                        << q.point.y << ", " << q.point.z << ")");
        for (int k = 0; k < 3; ++k) {
            EXPECT_TRUE(close(g0[k], c.direction[k], 1.0f))
                << "direction " << k << ": " << g0[k] << " vs " << c.direction[k];
            EXPECT_TRUE(close(g1[k], c.irradiance[k], strength))
                << "irradiance " << k << ": " << g1[k] << " vs " << c.irradiance[k];
        }
        EXPECT_TRUE(close(g0.w, c.distance, 0.0f)) << "distance: " << g0.w << " vs " << c.distance;
        const float fullFalloff = light.type == LightType::Directional ? 1.0f : strength / glm::length(light.emission);
        EXPECT_TRUE(close(g1.w, c.falloff, fullFalloff)) << "falloff: " << g1.w << " vs " << c.falloff;
        if (c.falloff <= 0.0f) ++dark;
        else if (c.falloff < 0.999f * fullFalloff) ++partial;
        else ++lit;
    }
    // The points exercise every case: full light, partial (cone band, quad cosine) and none.
    EXPECT_GT(lit, 100);
    EXPECT_GT(partial, 100);
    EXPECT_GT(dark, 100);
}

TEST(GBuffer, EncodeDecodeAndDiffuseAlbedoAgreeBetweenGlslAndCpp) {
    test::useHeadlessContext();
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f), box(-5.0f, 5.0f);
    std::normal_distribution<float> gauss(0.0f, 1.0f);
    const int count = 256;
    std::vector<shading::GBufferSurface> surfaces;
    std::vector<glm::vec4> in;
    for (int i = 0; i < count; ++i) {
        shading::GBufferSurface s;
        s.position = {box(rng), box(rng), box(rng)};
        s.normal = glm::normalize(glm::vec3(gauss(rng), gauss(rng), gauss(rng)));
        s.albedo = {unit(rng), unit(rng), unit(rng)};
        s.emission = glm::vec3(unit(rng), unit(rng), unit(rng)) * (i % 4 == 0 ? 10.0f : 0.0f);
        s.roughness = unit(rng);
        s.metallic = i % 5 == 0 ? 1.0f : unit(rng);
        s.specular = i % 7 == 0 ? 0.0f : unit(rng);
        s.transmission = i % 3 == 0 ? 0.0f : i % 3 == 1 ? 1.0f : unit(rng);
        surfaces.push_back(s);
        in.insert(in.end(), {glm::vec4(s.position, s.roughness), glm::vec4(s.normal, s.metallic),
                             glm::vec4(s.albedo, s.specular), glm::vec4(s.emission, s.transmission)});
    }
    gl::Handle surfaceBuffer = gl::createBuffer(in.size() * sizeof(glm::vec4), in.data(), 0);
    gl::Handle resultBuffer =
        gl::createBuffer(10 * std::size_t(count) * sizeof(glm::vec4), nullptr, GL_DYNAMIC_STORAGE_BIT);
    gl::Program program = gl::Program::compute("tests/gbuffer.comp");
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, surfaceBuffer.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, resultBuffer.id());
    program.use();
    program.set("uCount", count);
    glDispatchCompute(GLuint((count + 63) / 64), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<glm::vec4> gpu(10 * std::size_t(count));
    glGetNamedBufferSubData(resultBuffer.id(), 0, GLsizeiptr(gpu.size() * sizeof(glm::vec4)), gpu.data());

    for (int i = 0; i < count; ++i) {
        SCOPED_TRACE(testing::Message() << "surface " << i);
        const shading::GBufferSurface& s = surfaces[std::size_t(i)];
        const shading::GBufferTexels t = shading::encodeGBuffer(s);
        const shading::GBufferSurface d = shading::decodeGBuffer(t);
        const glm::vec3 diffuse = shading::diffuseAlbedo(s.albedo, s.metallic, s.specular, s.transmission);
        const glm::vec4 expected[10] = {t.position,
                                        t.normal,
                                        t.albedo,
                                        t.emission,
                                        glm::vec4(d.position, d.roughness),
                                        glm::vec4(d.normal, d.metallic),
                                        glm::vec4(d.albedo, d.specular),
                                        glm::vec4(d.emission, d.transmission),
                                        glm::vec4(diffuse, shading::gbufferHit(t.position) ? 1.0f : 0.0f),
                                        glm::vec4(shading::gbufferDiffuseAlbedo(t.position, t.albedo, t.emission), 0.0f)};
        for (int k = 0; k < 10; ++k)
            for (int c = 0; c < 4; ++c) {
                const float g = gpu[10 * std::size_t(i) + std::size_t(k)][c], e = expected[k][c];
                // The texels' diffuse albedo takes its transmission back from position.w = 1 + t,
                // whose rounding (an ulp of 1) a GLSL compiler may fold away: relative to 1.
                const float scale = k == 9 ? 1.0f : 0.0f;
                EXPECT_TRUE(close(g, e, scale)) << "value " << k << "." << c << ": " << g << " vs " << e;
            }
        // The round trip gives the surface back, and the diffuse albedo is the BRDF's.
        for (int c = 0; c < 3; ++c) {
            EXPECT_FLOAT_EQ(d.position[c], s.position[c]);
            EXPECT_NEAR(d.normal[c], s.normal[c], 1e-6f);
            EXPECT_FLOAT_EQ(d.albedo[c], s.albedo[c]);
            EXPECT_FLOAT_EQ(d.emission[c], s.emission[c]);
            EXPECT_FLOAT_EQ(diffuse[c], (1.0f - s.transmission) * (1.0f - s.metallic) * (1.0f - s.specular) * s.albedo[c]);
        }
        EXPECT_EQ(d.roughness, s.roughness);
        EXPECT_EQ(d.metallic, s.metallic);
        EXPECT_EQ(d.specular, s.specular);
        EXPECT_NEAR(d.transmission, s.transmission, 1e-6f);
        EXPECT_TRUE(shading::gbufferHit(t.position));
    }
    EXPECT_FALSE(shading::gbufferHit(glm::vec4(1.0f, 2.0f, 3.0f, 0.0f)));  // a cleared texel
}

TEST(Constants, PiIsPi) {
    EXPECT_EQ(shading::kPi, float(shading::kPiDouble));
    EXPECT_FLOAT_EQ(shading::kInvPi * shading::kPi, 1.0f);
    EXPECT_DOUBLE_EQ(std::acos(-1.0), shading::kPiDouble);
}
