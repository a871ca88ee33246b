// The path tracer's light-vertex connections (gi/pathtrace/light_paths.h): the same image in
// expectation as unidirectional paths (MIS weights that sum to one over both strategies), an
// analytic interreflection answer, and less noise where the indirect light comes from a small
// bright patch.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "gi/pathtrace/path_tracer.h"
#include "scenes/primitives.h"
#include "shaders/shared/constants.h"

using namespace voxgi;

namespace {

Image render(const Scene& scene, bool lightPaths, int spp, std::uint64_t seed, int maxBounces = 0) {
    PathTracerOptions o;
    o.lightPaths = lightPaths;
    o.seed = seed;
    o.maxBounces = maxBounces;
    PathTracer tracer(scene, o);
    tracer.render(spp);
    return tracer.image();
}

double layerMean(const Image& image, const char* layer) {
    const ImageLayer& l = *image.find(layer);
    double sum = 0.0;
    for (float v : l.data) sum += double(v);
    return sum / double(l.data.size());
}

// Mean squared difference of two renders' layer: twice the per-pixel variance of either.
double layerMse(const Image& a, const Image& b, const char* layer) {
    const ImageLayer &la = *a.find(layer), &lb = *b.find(layer);
    double sum = 0.0;
    for (std::size_t i = 0; i < la.data.size(); ++i) sum += std::pow(double(la.data[i]) - double(lb.data[i]), 2.0);
    return sum / double(la.data.size());
}

// A closed 4 m room lit by a point lamp 0.25 m above the floor and a spot on the ceiling
// aimed at a glossy wall; the camera looks at the ceiling, which sees the lamp's bright floor
// patch only through the bounce.
Scene lampRoom() {
    Scene s;
    Material wall;
    wall.albedo = glm::vec3(0.7f, 0.6f, 0.5f);
    Material glossy;
    glossy.albedo = glm::vec3(0.4f, 0.5f, 0.7f);
    glossy.specular = 0.04f;
    glossy.roughness = 0.4f;
    s.materials = {wall, glossy};
    s.meshes.push_back(makeBox(glm::scale(glm::mat4(1.0f), glm::vec3(4.0f)), 0, true));
    s.meshes.push_back(makeQuad({glm::vec3(1.99f, -2.0f, -2.0f), glm::vec3(1.99f, -2.0f, 2.0f),
                                 glm::vec3(1.99f, 2.0f, 2.0f), glm::vec3(1.99f, 2.0f, -2.0f)},
                                1));
    Light lamp;
    lamp.type = LightType::Point;
    lamp.position = glm::vec3(-1.0f, -1.75f, 0.5f);
    lamp.emission = glm::vec3(3.0f);
    Light spot;
    spot.type = LightType::Spot;
    spot.position = glm::vec3(0.0f, 1.9f, 0.0f);
    spot.direction = glm::normalize(glm::vec3(1.0f, -0.5f, 0.0f));
    spot.emission = glm::vec3(4.0f);
    s.lights = {lamp, spot};
    s.camera.eye = glm::vec3(-1.5f, -1.0f, 1.8f);
    s.camera.target = glm::vec3(0.5f, 2.0f, -0.5f);
    s.camera.fovYDegrees = 70.0f;
    s.camera.width = s.camera.height = 16;
    return s;
}

// The lamp room lit instead by a square panel `side` across (a quad light: an emitter, which
// next-event estimation samples by solid angle and camera paths can also hit) under its
// ceiling.
Scene panelRoom(float side) {
    Scene s = lampRoom();
    Light panel;
    panel.type = LightType::Quad;
    panel.position = glm::vec3(-0.5f * side, 1.9f, -0.5f * side);
    panel.edgeU = glm::vec3(side, 0.0f, 0.0f);
    panel.edgeV = glm::vec3(0.0f, 0.0f, side);  // emits downwards
    panel.emission = glm::vec3(4.0f / (side * side));
    s.lights = {panel};
    s.camera.target = glm::vec3(0.5f, -2.0f, -0.5f);
    return s;
}

// A point lamp of `intensity` a little off the centre of a closed diffuse sphere of `radius`
// and albedo `rho`, seen from inside.
Scene lampInSphere(float radius, float rho, float intensity) {
    Scene s;
    Material m;
    m.albedo = glm::vec3(rho);
    s.materials.push_back(m);
    s.meshes.push_back(makeSphere(glm::scale(glm::mat4(1.0f), glm::vec3(radius)), 0, 96, true));
    Light lamp;
    lamp.type = LightType::Point;
    lamp.position = glm::vec3(0.0f, 0.3f, 0.0f);
    lamp.emission = glm::vec3(intensity);
    s.lights.push_back(lamp);
    s.camera.eye = glm::vec3(0.0f, -0.3f, 0.0f);
    s.camera.target = glm::vec3(0.2f, -0.3f, -1.0f);
    s.camera.fovYDegrees = 20.0f;
    s.camera.width = s.camera.height = 8;
    return s;
}

}  // namespace

TEST(PathTracerLightPaths, PointLightInADiffuseSphereMatchesTheAnalyticInterreflection) {
    // Inside a sphere of radius R and albedo rho, a point light of intensity I at the centre
    // gives every wall point irradiance I / R^2; one more scattering turns uniform radiance L
    // into rho L. After at most B scatterings the indirect layer (two or more) is
    // rho / pi * I / R^2 * (rho + ... + rho^(B-1)).
    const float radius = 2.0f, rho = 0.6f, intensity = 5.0f;
    const int bounces = 4;
    const Scene s = lampInSphere(radius, rho, intensity);
    // The lamp is off-centre (so the camera does not sit on it), which leaves the bounced light
    // uniform only to first order: the indirect layer is compared in the mean over the image
    // against the centred answer, within 2 %.
    double sum = 0.0;
    for (float q = 1.0f, k = 1; k < bounces; ++k) sum += (q *= rho);
    const double expected = rho / shading::kPi * intensity / (radius * radius) * sum;
    for (bool lightPaths : {false, true}) {
        const double indirect = layerMean(render(s, lightPaths, 512, 1, bounces), "indirect");
        EXPECT_NEAR(indirect, expected, 0.02 * expected) << (lightPaths ? "with" : "without") << " light paths";
    }
}

TEST(PathTracerLightPaths, LongLightSubpathsKeepTheAnalyticInterreflectionAtAnyDepth) {
    // The same sphere, with paths long enough that light subpaths stop at kMaxLightVertices
    // surfaces before paths do (12 scatterings), and unlimited (roulette): every scattering
    // order is counted once, whichever strategies can make it (the answer sums rho^k to
    // B - 1, or to infinity).
    const float radius = 2.0f, rho = 0.9f, intensity = 5.0f;
    const Scene s = lampInSphere(radius, rho, intensity);
    const double scale = rho / shading::kPi * intensity / (radius * radius);
    for (int bounces : {12, 0}) {
        double sum = 0.0;
        if (bounces > 0)
            for (float q = 1.0f, k = 1; k < bounces; ++k) sum += (q *= rho);
        else
            sum = rho / (1.0 - rho);
        const double expected = scale * sum;
        const double indirect = layerMean(render(s, true, 512, 2, bounces), "indirect");
        EXPECT_NEAR(indirect, expected, 0.02 * expected) << "max bounces " << bounces;
    }
}

TEST(PathTracerLightPathsConvergence, EachScatteringOrderMatchesUnidirectionalPaths) {
    // Paths cut at B scatterings: with connections through light subpaths of up to B - 1
    // surfaces, the image's mean is the unidirectional one, order by order, for delta lights
    // and for an emitter. The unidirectional mean's standard error is about 0.25 % at 2048
    // samples (seeds 1-6 spread so at 512), the connected one's a third of it.
    // A large panel: camera paths hit it often, so that strategy's weight matters too.
    for (const Scene& s : {lampRoom(), panelRoom(0.6f), panelRoom(3.0f)})
        for (int bounces : {2, 3, 5}) {
            const double with = layerMean(render(s, true, 512, 7, bounces), "indirect");
            const double without = layerMean(render(s, false, 2048, 7, bounces), "indirect");
            EXPECT_NEAR(with, without, 0.015 * without) << s.lights[0].area() << " m2 first light, max bounces " << bounces;
        }
}

TEST(PathTracerLightPaths, AnEmittersIndirectLightHasLessNoiseWithConnections) {
    // The panel lights a patch of floor that lights the rest of the room: connections land
    // on the patch by construction. Per-pixel variance of the indirect layer from two seeds.
    const Scene s = panelRoom(0.6f);
    const double varianceWith = 0.5 * layerMse(render(s, true, 64, 5), render(s, true, 64, 6), "indirect");
    const double varianceWithout = 0.5 * layerMse(render(s, false, 64, 5), render(s, false, 64, 6), "indirect");
    EXPECT_LT(varianceWith, 0.7 * varianceWithout) << varianceWith << " against " << varianceWithout;
}

TEST(PathTracerLightPaths, ConnectionsConvergeToTheUnidirectionalImageWithLessNoise) {
    const Scene s = lampRoom();
    // Both estimators at 1024 samples per pixel: the same image to within their noise.
    const Image with = render(s, true, 1024, 3), without = render(s, false, 1024, 3);
    const double meanWith = layerMean(with, "indirect"), meanWithout = layerMean(without, "indirect");
    EXPECT_NEAR(meanWith, meanWithout, 0.01 * meanWithout);
    // Per pixel too: the difference is noise (the per-pixel variances, from two seeds each at
    // 64 samples, scaled to 1024), not a pattern.
    const Image with0 = render(s, true, 64, 5), with1 = render(s, true, 64, 6);
    const Image without0 = render(s, false, 64, 5), without1 = render(s, false, 64, 6);
    const double varianceWith = 0.5 * layerMse(with0, with1, "indirect");
    const double varianceWithout = 0.5 * layerMse(without0, without1, "indirect");
    const double expectedMse = (varianceWith + varianceWithout) * 64.0 / 1024.0;
    EXPECT_LT(layerMse(with, without, "indirect"), 2.0 * expectedMse);
    // The ceiling's light comes from the lamp's floor patch: connections land there by
    // construction, BSDF samples rarely.
    EXPECT_LT(varianceWith, 0.5 * varianceWithout) << varianceWith << " against " << varianceWithout;
    // Direct light is untouched by them.
    EXPECT_NEAR(layerMean(with, "direct"), layerMean(without, "direct"), 0.01 * layerMean(without, "direct"));
}

TEST(PathTracerLightPaths, ImagesAreTheSameForAnySampleBatching) {
    // Light subpaths are keyed by the sample index, so rendering 6 samples at once or as 2 + 4
    // gives the same image, and samplePixel() retraces render()'s paths.
    const Scene s = lampRoom();
    PathTracerOptions o;
    PathTracer once(s, o), split(s, o);
    once.render(6);
    split.render(2);
    split.render(4);
    const Image imageOnce = once.image(), imageSplit = split.image();
    const ImageLayer &a = *imageOnce.find("beauty"), &b = *imageSplit.find("beauty");
    ASSERT_EQ(a.data.size(), b.data.size());
    for (std::size_t i = 0; i < a.data.size(); ++i) ASSERT_EQ(a.data[i], b.data[i]) << i;
    const PathSample first = once.samplePixel(3, 4, 0), again = split.samplePixel(3, 4, 0);
    EXPECT_EQ(first.indirect, again.indirect);
    EXPECT_EQ(first.rays, again.rays);
}
