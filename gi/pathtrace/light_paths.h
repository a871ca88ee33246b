// Light subpaths for the path tracer's light-vertex connections: rays leave the point and spot
// lights and scatter on, and every surface they meet with a smooth BSDF is kept as a light
// vertex. Camera paths connect every vertex to one of the pool's vertices, picked at random,
// with MIS over every way the same path can be made: next-event estimation at its last
// surface, or a connection across any of its edges (a bidirectional path tracer, Veach 1997
// ch. 10, restricted to delta lights and to camera subpaths of at least one surface, with the
// shared light-vertex pool of Davidovic et al. 2014 and the recursive MIS quantities of
// Georgiev 2012, "Implementing vertex connection and merging").
//
// Why: light that reaches a point from a small, bright patch of surface (the floor under a
// lamp, the wall that floor lights) is found by BSDF sampling only when a bounce happens to
// hit the patch; a light subpath lands there by construction, in proportion to the light's
// power. The sun, area emitters and the sky keep unidirectional sampling only
// (gi/pathtrace/lights.h says why).
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace voxgi::pt {

// Surfaces a light subpath keeps at most: connections through longer light subpaths are not
// made, and the MIS weights leave those strategies out (Integrator::connect). Bounds the pool's
// memory; light with more scatterings than this still arrives by the shorter strategies.
constexpr int kMaxLightVertices = 8;

// Light vertices each camera-path vertex weighs for a connection; one of them, picked in
// proportion to its unoccluded contribution, gets the shadow ray (Integrator::connect). More
// candidates find the few light vertices near a camera vertex (the pool holds the whole
// scene's, and the near ones carry most of its light) for the price of evaluating them. Per-sample
// variance x CPU time relative to one candidate, at 128^2 (docs/reference.md): Sibenik 0.74 / 0.73
// / 0.73 / 0.72 with 2 / 3 / 4 / 6, the Cornell box 0.97 / 1.02 / 1.07 / 1.19.
constexpr int kConnections = 2;

struct LightVertex {
    static constexpr std::uint32_t kNone = 0xFFFFFFFFu;
    glm::vec3 position{0.0f};
    std::uint32_t material = kNone;  // kNone: the subpath left the scene or hit a delta surface
    glm::vec3 geometricNormal{0.0f};  // unit, as stored (the triangle's winding)
    std::uint32_t scatterings = 0;    // surfaces on the light subpath up to and including this one
    glm::vec3 shadingNormal{0.0f};    // unit, as stored
    float misArea = 0.0f;             // 1 / (pdf, per unit area here, of the light subpath reaching here)^2
    glm::vec3 albedo{0.0f};
    float misLonger = 0.0f;           // the camera subpath's longer strategies, relative (Georgiev's dVC)
    glm::vec3 toLight{0.0f};          // unit, towards the previous vertex of the light subpath
    // The light subpath's throughput over the geometric cosine towards the previous vertex:
    // times the vertex's f |cos| towards it and the connection's geometry term, the
    // contribution of the connected path (the same product of f |cos| a camera path forms).
    glm::vec3 flux{0.0f};
    bool valid() const { return material != kNone; }
};

// The light vertices of one sample index: the kept vertices of `paths` light subpaths, in
// subpath order.
struct LightVertices {
    std::vector<LightVertex> vertices;
    // The vertex at u in [0, 1) along the pool (non-empty).
    const LightVertex& pick(float u) const {
        return vertices[std::min(std::size_t(u * float(vertices.size())), vertices.size() - 1)];
    }
    std::uint32_t paths = 0;
    std::uint64_t rays = 0;  // traced to build them
};

}  // namespace voxgi::pt
