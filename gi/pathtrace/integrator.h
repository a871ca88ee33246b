// One path from a camera ray: the light transport part of the path tracer, separate from
// pixels, tiles and accumulation (gi/pathtrace/path_tracer.cpp).
#pragma once

#include <algorithm>
#include <vector>

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
    // `caustics`: PathTracerOptions::caustics.
    Integrator(const Scene& scene, const RayTracer& tracer, int maxBounces, bool caustics = true);
    // Decision 0 of `sampler` is the caller's (the pixel position); bounce k uses 1 + 5k..5 + 5k.
    // With `lightVertices` (this sample index's, light_paths.h), every vertex of the path is also
    // connected to one of them (kConnections weighed, one traced); without, the path is
    // unidirectional.
    // `firstHit`: the camera ray's hit when the caller traced it already (a tile's camera rays
    // go through Embree together, RayTracer::intersectCoherent); counted in the path's rays.
    PathSample trace(glm::vec3 origin, glm::vec3 direction, const PathSampler& sampler,
                     const LightVertices* lightVertices = nullptr, const RayHit* firstHit = nullptr) const;
    // One camera path's start, for traceBatch.
    struct PathStart {
        glm::vec3 origin{0.0f}, direction{0.0f};
        PathSampler sampler;
        const RayHit* firstHit = nullptr;  // as trace()'s
    };
    // trace() of n paths at once, out[i] for starts[i]: the same samples, in less time (the
    // paths take turns at each stage of a bounce, so one path's cache misses load while the
    // others work).
    void traceBatch(const PathStart* starts, int n, const LightVertices* lightVertices, PathSample* out) const;

    // Whether any light emits light subpaths (the scene has point or spot lights or emitters)
    // and paths are long enough to use them (two scatterings or more).
    bool tracesLightPaths() const { return lights_.emitsRays() && maxBounces_ >= 2; }
    // Surfaces a light subpath keeps at most: kMaxLightVertices, and one fewer than a path may
    // scatter (a connection adds at least one camera surface).
    int maxLightVertices() const { return std::min(kMaxLightVertices, maxBounces_ - 1); }
    // Light subpath `sampler` (decision 0: the light and the direction; 1: the point on an
    // emitter; surface j: 2j its BSDF sample, 2j + 1 roulette): appends its light vertices to
    // `out` and returns the rays it traced.
    std::uint32_t traceLightPath(const PathSampler& sampler, std::vector<LightVertex>& out) const;

private:
    // What the MIS weights of light-vertex connections need from the camera subpath so far:
    // for its last kMaxLightVertices surfaces v_k (k = 1 at the first hit), the area pdf of the
    // camera subpath reaching v_k and that of a light subpath reaching v_(k-1) from v_k (known
    // once the camera subpath leaves v_k), and the factor that turns a solid-angle pdf at v_k
    // towards v_(k-1) into one per unit area at v_(k-1).
    struct CameraHistory {
        struct Surface {
            float arrival = 0.0f;         // camera subpath reaching v_k (0 after a delta lobe)
            float reverse = 0.0f;         // light subpath reaching v_(k-1) from v_k (0: none)
            float toPreviousArea = 0.0f;  // |cos| at v_(k-1) / distance^2
        };
        int surfaces = 0;  // k of the newest surface
        Surface& at(int k) { return ring[std::size_t(k % kMaxLightVertices)]; }
        const Surface& at(int k) const { return ring[std::size_t(k % kMaxLightVertices)]; }
        Surface ring[kMaxLightVertices];
    };

    // A camera path between the stages of traceBatch (integrator.cpp).
    struct PathState;
    // The stages of one bounce that traceBatch does not do itself: Embree's traversal; emission
    // and the delta lights' shadow rays (path.hit built); the albedo, light sampling,
    // connections and the next direction. Each sets path.done when the path ends.
    void findSurface(PathState& path) const;
    void enterSurface(PathState& path) const;
    void leaveSurface(PathState& path) const;

    // The shadow rays towards the first kEarlyDeltaShadows delta lights (uDisc: the direction in
    // a sun's disc), traced before the albedo is known: `bsdf` may hold any albedo (only
    // Bsdf::mayReflect is read), and the albedo's texels load while Embree traces. Bit i of
    // the result: light i is visible (and was traced).
    static constexpr std::size_t kEarlyDeltaShadows = 64;
    // The samples of the first kKeptDeltaSamples delta lights, kept for sampleLights (a sun's
    // disc sample costs a sine and a cosine; most scenes have one or two delta lights).
    static constexpr std::size_t kKeptDeltaSamples = 2;
    struct EarlyDeltas {
        std::uint64_t visible = 0;  // bit i: light i is visible (and was traced)
        LightSample kept[kKeptDeltaSamples];
    };
    // The shadow ray of delta-light sample `ls` at the hit: true when nothing blocks it.
    bool deltaVisible(const RayHit& hit, const LightSample& ls, std::uint32_t& rays) const;
    void deltaShadows(const class Bsdf& bsdf, const RayHit& hit, glm::vec2 uDisc, EarlyDeltas& out, std::uint32_t& rays) const;
    // Light after one more scattering at the hit, sampled from the lights (NEE) with MIS.
    // u: the emitter point or sky direction (x, y) and the choice between them (z); uDisc: the
    // direction in a sun's disc; early: deltaShadows' answer at this hit. `history`
    // (null: no light subpaths) weighs delta-light samples against the light-vertex
    // connections that make the same paths.
    glm::vec3 sampleLights(const class Bsdf& bsdf, const RayHit& hit, glm::vec3 u, glm::vec2 uDisc,
                           const EarlyDeltas& early, const CameraHistory* history, std::uint32_t& rays) const;
    // A connection of the hit (the camera subpath's newest surface) to light vertex u * size of
    // `pool`, before its shadow ray: the joined path's contribution, MIS-weighted over every
    // strategy that makes it, if unoccluded. False when it carries nothing.
    struct Connection {
        glm::vec3 contribution{0.0f};
        glm::vec3 from{0.0f}, to{0.0f}, toNormal{0.0f};  // the shadow segment
        int scatterings = 0;
    };
    bool connection(const class Bsdf& bsdf, const RayHit& hit, const LightVertices& pool, float u,
                    const CameraHistory& history, Connection& out) const;
    // Light after more scatterings: kConnections connections of the hit, one of them traced
    // (light_paths.h). Deposited through `deposit(scatterings, radiance)`.
    template <class Deposit>
    void connect(const class Bsdf& bsdf, const RayHit& hit, const LightVertices& pool, glm::vec2 u,
                 const CameraHistory& history, Deposit deposit, std::uint32_t& rays) const;
    // The area pdf of a light subpath reaching the camera subpath's previous surface from its
    // newest one (at `bsdf`), having come there along `onwards` (pointing away).
    static float reverseArea(const class Bsdf& bsdf, glm::vec3 onwards, const CameraHistory& history);
    // The MIS weights' sum over the strategies that give a light subpath more of the path's
    // surfaces than the one evaluated, relative to it: the evaluated one joins the camera
    // subpath's newest surface v_k to a light subpath of `lightSurfaces` surfaces, which
    // reaches v_k with area pdf `lightAreaAtK`; reverseAtK() is the area pdf of a light subpath
    // going on from v_k to v_(k-1).
    template <class ReverseAtK>
    float longerLightSubpaths(const CameraHistory& history, float lightAreaAtK, ReverseAtK reverseAtK,
                              int lightSurfaces) const;
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
    bool caustics_;
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
