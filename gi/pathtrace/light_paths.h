// Light subpaths of one segment for the path tracer's light-vertex connections: rays leave the
// point and spot lights, and the surface each first hits is kept as a light vertex.
// Camera paths connect every vertex to one of them, picked at random, with MIS against the
// unidirectional path that reaches the same light vertex by BSDF sampling and then takes the
// light by next-event estimation (a restricted bidirectional path tracer: Veach 1997 ch. 10,
// with the shared light-vertex pool of Davidovic et al. 2014).
//
// Why: light that reaches a point from a small, bright patch of surface (the floor under a
// lamp) is found by BSDF sampling only when a bounce happens to hit the patch; a light subpath
// lands there by construction, in proportion to the light's irradiance. The sun, area emitters
// and the sky keep unidirectional sampling only (gi/pathtrace/lights.h says why).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace voxgi::pt {

struct LightVertex {
    static constexpr std::uint32_t kNone = 0xFFFFFFFFu;
    glm::vec3 position{0.0f};
    std::uint32_t material = kNone;  // kNone: the subpath left the scene or hit a delta surface
    glm::vec3 geometricNormal{0.0f};  // unit, as stored (the triangle's winding)
    float pdfArea = 0.0f;             // light choice x emission pdf, per unit area at `position`
    glm::vec3 shadingNormal{0.0f};    // unit, as stored
    glm::vec3 albedo{0.0f};
    glm::vec3 toLight{0.0f};          // unit, towards the light
    // Emitted intensity over (pdf x geometric cosine towards the light): times the vertex's f |cos| towards the light and the connection's geometry
    // term, the contribution of the connected path.
    glm::vec3 flux{0.0f};
    bool valid() const { return material != kNone; }
};

// The light vertices of one sample index: vertex j is light subpath j of that index.
struct LightVertices {
    std::vector<LightVertex> vertices;
    std::uint64_t rays = 0;  // traced to build them
};

}  // namespace voxgi::pt
