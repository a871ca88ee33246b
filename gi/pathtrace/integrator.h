// One path from a camera ray: the light transport part of the path tracer, separate from
// pixels, tiles and accumulation (gi/pathtrace/path_tracer.cpp).
#pragma once

#include "gi/pathtrace/environment.h"
#include "gi/pathtrace/light_paths.h"
#include "gi/pathtrace/lights.h"
#include "gi/pathtrace/path_tracer.h"
#include "gi/pathtrace/sampler.h"
#include "gi/raytrace/ray_tracer.h"

namespace voxgi::pt {

// A hard stop for paths that lose no energy (roulette never ends those: a mirror maze, light
// trapped in glass). Any surface with albedo below 0.998 has ended its path by then with
// probability above 1 - 1e-8, so the bias this costs is far below any test's resolution.
constexpr int kBounceGuard = 10000;

class Integrator {
public:
    Integrator(const Scene& scene, const RayTracer& tracer, int maxBounces);
    // Decision 0 of `sampler` is the caller's (the pixel position); bounce k uses 1 + 5k..5 + 5k.
    // With `lightVertices` (this sample index's, light_paths.h), every vertex of the path is also
    // connected to one of them; without, the path is unidirectional.
    PathSample trace(glm::vec3 origin, glm::vec3 direction, const PathSampler& sampler,
                     const LightVertices* lightVertices = nullptr) const;

    // Whether any light emits light subpaths (the scene has point or spot lights) and
    // paths are long enough to use them (two scatterings or more).
    bool tracesLightPaths() const { return lights_.emitsRays() && maxBounces_ >= 2; }
    // Light subpath `sampler` (decision 0) into `out` (invalid when it found no usable
    // surface); returns the rays it traced.
    std::uint32_t traceLightPath(const PathSampler& sampler, LightVertex& out) const;

private:
    // Light after one more scattering at the hit, sampled from the lights (NEE) with MIS.
    // u: the emitter point or sky direction (x, y) and the choice between them (z); uDisc: the
    // direction in a sun's disc. arrivalPdfArea: the area pdf of
    // the hit through the previous vertex's BSDF sample, for weighting delta-light samples
    // against light-vertex connections from that vertex (0: no connection could make the path).
    glm::vec3 sampleLights(const class Bsdf& bsdf, const RayHit& hit, glm::vec3 u, glm::vec2 uDisc,
                           float arrivalPdfArea, std::uint32_t& rays) const;
    // Light after two more scatterings: the hit joined to light vertex u * size of `pool`, with
    // MIS against reaching that vertex by this BSDF's sample.
    glm::vec3 connect(const class Bsdf& bsdf, const RayHit& hit, const LightVertices& pool, float u,
                      std::uint32_t& rays) const;
    // Whether anything lies between `from` (a ray origin, leavingPoint) and emitter point q
    // (normal nq).
    bool segmentOccluded(glm::vec3 from, glm::vec3 q, glm::vec3 nq) const;

    const Scene& scene_;
    const RayTracer& tracer_;
    // The probability that a next-event sample goes to the sky rather than an emitter.
    float environmentShare() const;

    LightSampler lights_;
    EnvironmentSampler environment_;
    int maxBounces_;
    float sceneScale_;
};

// The scene size offsetOrigin scales with: its bounding box's diagonal.
float rayOffsetScale(const Scene& scene);
// Origin offset so a ray leaving a surface does not hit it again: along the geometric normal,
// on the side the ray leaves to, relative to the scene size and the coordinates' magnitude.
glm::vec3 offsetOrigin(glm::vec3 p, glm::vec3 geometric, glm::vec3 direction, float sceneScale);
// The origin of a ray leaving `hit` in `direction`: offsetOrigin of the smooth surface point
// (RayHit::smoothPosition) when it leaves to the side the shading normal faces, else of the hit.
glm::vec3 leavingPoint(const RayHit& hit, glm::vec3 direction, float sceneScale);

}  // namespace voxgi::pt
