// Next-event estimation: every light of the scene as something a shading point can sample.
// Point, spot and directional lights are deltas (sampled every time), evaluated by the shared
// light model (shaders/shared/light_model.h). Quad lights are not: the path tracer sees them as
// the emissive triangles of their geometry (Scene::addQuadLightGeometry), which BSDF sampling
// can hit, so that light and BSDF samples of them are weighted by MIS. Emissive triangles are
// picked in proportion to their power and sampled uniformly by area.
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
};

class LightSampler {
public:
    explicit LightSampler(const Scene& scene);

    // Delta lights are evaluated exhaustively: index in [0, deltaCount()).
    std::size_t deltaCount() const { return deltas_.size(); }
    // Incident light from delta light `index` (unoccluded) at `p`: its irradiance at normal
    // incidence (pdf 0).
    LightSample sampleDelta(std::size_t index, glm::vec3 p) const;

    bool hasEmissiveTriangles() const { return !triangles_.empty(); }
    // One emissive-triangle sample; radiance is Le / pdf (solid angle), zero on the back side.
    LightSample sampleEmissive(glm::vec3 p, float u0, float u1, float u2) const;
    // Solid-angle pdf with which sampleEmissive picks a point of (mesh, triangle) seen at
    // squared distance d2 under cosine cosLight (> 0) to the emitter's normal.
    float emissivePdf(std::uint32_t mesh, std::uint32_t triangle, float d2, float cosLight) const;

private:
    struct Emitter {
        glm::vec3 a, e1, e2, normal;
        glm::vec3 emission;
        float area;
    };
    std::vector<shading::PackedLight> deltas_;
    std::vector<Emitter> triangles_;
    std::vector<float> cdf_;                       // cumulative selection probability
    std::vector<std::size_t> meshFirstTriangle_;  // global triangle index of each mesh's first one
    std::vector<float> selectionPdf_;              // per global triangle: probability / area
};

}  // namespace voxgi::pt
