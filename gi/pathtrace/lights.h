// Next-event estimation: every light of the scene as something a shading point can sample.
// Point, spot and directional lights are deltas (sampled every time), evaluated by the shared
// light model (shaders/shared/light_model.h). Quad lights are not: the path tracer sees them as
// the emissive triangles of their geometry (Scene::addQuadLightGeometry), which BSDF sampling
// can hit, so that light and BSDF samples of them are weighted by MIS.
//
// Emitters are picked in proportion to their power. A rectangular quad light is one emitter,
// sampled uniformly in the solid angle it subtends (Urena, Fajardo and King 2013, "An
// area-preserving parametrization for spherical rectangles"): no 1/r^2 or cosine in the
// estimate, so the floor under a light and the walls beside it are as quiet as the far end of
// the room. Seen under a tiny solid angle, where that mapping loses precision and gains
// nothing, it is sampled by area. Every other emissive triangle is sampled uniformly by area.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "scenes/scene.h"
#include "shaders/shared/light_model.h"

namespace voxgi::pt {

struct LightSample {
    glm::vec3 direction{0.0f};   // unit, from the shading point towards the light
    float distance = 0.0f;       // to the light point; infinity for directional lights
    glm::vec3 radiance{0.0f};    // arriving radiance (area) or irradiance-like value (delta) / pdf
    float pdf = 0.0f;            // solid-angle pdf for area lights; 0 marks a delta light
    glm::vec3 position{0.0f};    // area lights: the sampled point on the emitter
    glm::vec3 normal{0.0f};      // area lights: the emitter's unit normal (its emitting side)
    float lightPathPdfArea = 0.0f;  // area lights: the pdf, per unit area, of a light subpath starting at `position`
};

// A ray leaving a light, the first segment of a light subpath (gi/pathtrace/light_paths.h).
struct EmittedRay {
    glm::vec3 origin{0.0f};
    glm::vec3 direction{0.0f};   // unit, the way the light travels
    glm::vec3 intensity{0.0f};   // along `direction` (W/sr; an emitter's radiance x cosine)
    // Light choice x direction pdf (per sr); for an emitter also x the point's pdf per unit area.
    float pdf = 0.0f;
    // Emitters only (`emitter` >= 0): the point's unit normal.
    glm::vec3 normal{0.0f};
    std::int32_t emitter = -1;
};

class LightSampler {
public:
    // `scene` holds the quad lights' geometry (Scene::addQuadLightGeometry).
    explicit LightSampler(const Scene& scene);

    // Delta lights are evaluated exhaustively: index in [0, deltaCount()).
    std::size_t deltaCount() const { return deltas_.size(); }
    // Whether a sun has a disc (sampleDelta's u matters).
    bool hasSunDisc() const { return sunDisc_; }
    // Incident light from delta light `index` (unoccluded) at `p`: its irradiance at normal
    // incidence (pdf 0). A sun with a disc comes from the direction of its disc that u in
    // [0,1)^2 picks: it is sampled here only, never found by BSDF rays (docs/reference.md).
    LightSample sampleDelta(std::size_t index, glm::vec3 p, glm::vec2 u) const;

    // Light subpaths leave point and spot lights and emitters, never the sun: it lights whole
    // floors and facades, which BSDF sampling finds anyway, and its rays would have to start on
    // a disc across the scene's bounding sphere, most of them landing on roofs (Sponza: no less
    // error per sample, 26 % fewer samples in the same time; docs/reference.md).
    // A light picked in proportion to its power (u.z), then a ray from it (u.x, u.y): uniform
    // over the sphere (point) or over the outer cone (spot); from an emitter, a point uniform
    // over its area (uPoint) and a cosine-weighted direction.
    bool emitsRays() const { return !rayCdf_.empty() || emitterRayShare_ > 0.0f; }
    EmittedRay sampleEmission(glm::vec3 u, glm::vec2 uPoint) const;
    // The pdf, per unit area at a point y, of sampleEmission's rays reaching y from delta light
    // `index`, y seeing the light along unit `toLight` at `distance` under geometric cosine
    // `cosAtY` (> 0); 0 for the sun.
    float emissionPdfArea(std::size_t index, glm::vec3 toLight, float distance, float cosAtY) const;
    // The pdf, per unit area, of sampleEmission starting at a point of (mesh, triangle), an
    // emitter's.
    float emissionPointPdf(std::uint32_t mesh, std::uint32_t triangle) const;
    // sampleEmitter's solid-angle pdf, from `from`, of the point `at` of emitter `emitter`
    // (EmittedRay::emitter), seen under cosine cosLight (> 0).
    float emitterPdf(std::int32_t emitter, glm::vec3 from, glm::vec3 at, float cosLight) const;

    bool hasEmitters() const { return !cdf_.empty(); }
    // One emitter sample seen from p: `u` places the point, `select` picks the emitter. radiance
    // is Le / pdf (solid angle), zero on the back side.
    LightSample sampleEmitter(glm::vec3 p, glm::vec2 u, float select) const;
    // Solid-angle pdf with which sampleEmitter, from `from`, picks the point `at` of (mesh,
    // triangle), seen under cosine cosLight (> 0) to the emitter's normal.
    float emitterPdf(std::uint32_t mesh, std::uint32_t triangle, glm::vec3 from, glm::vec3 at, float cosLight) const;

private:
    struct Triangle {
        glm::vec3 a, e1, e2, normal;
        glm::vec3 emission;
        float area;
    };
    struct Rectangle {
        glm::vec3 corner, ex, ey, normal;  // ex, ey unit; normal = cross(ex, ey), the emitting side
        float width, height;
        glm::vec3 emission;
    };
    // Either a rectangle or a triangle, with the probability of picking it.
    struct Emitter {
        bool rectangle;
        std::uint32_t index;
        float probability;
    };
    LightSample sampleRectangle(const Rectangle& r, glm::vec3 p, glm::vec2 u) const;
    float area(const Emitter& e) const;
    // The pdf, per unit area, of a light subpath starting at a point of `e`.
    float emissionPointPdf(const Emitter& e) const;
    // The emitter whose cumulative probability first reaches `select` in [0, 1).
    std::size_t pickEmitter(float select) const;
    LightSample sampleTriangle(const Triangle& t, glm::vec3 p, glm::vec2 u) const;
    float rectanglePdf(const Rectangle& r, glm::vec3 from, glm::vec3 at, float cosLight) const;

    // Per delta: the pdf of its emitted direction (per sr), uniform over what it can emit
    // into, times the probability of choosing it.
    float emissionPdf(std::size_t index) const;

    std::vector<shading::PackedLight> deltas_;
    bool sunDisc_ = false;
    // Per delta: the probability a light subpath starts there, in proportion to emitted power
    // (0 for the sun); the cumulative sums.
    std::vector<float> rayProbability_, rayCdf_;  // probabilities include the share of deltas; the cdf is among them
    // The share of light subpaths that start on emitters (by power: pi x radiance x area).
    float emitterRayShare_ = 0.0f;
    std::vector<Rectangle> rectangles_;
    std::vector<Triangle> triangles_;
    std::vector<Emitter> emitters_;
    std::vector<float> cdf_;                       // cumulative selection probability over emitters_
    std::vector<std::size_t> meshFirstTriangle_;   // global triangle index of each mesh's first one
    std::vector<std::int32_t> meshRectangle_;      // per mesh: its rectangle emitter, or -1
    std::vector<float> rectangleProbability_;      // per rectangle
    std::vector<float> trianglePdfArea_;           // per global triangle: selection probability / area
};

}  // namespace voxgi::pt
