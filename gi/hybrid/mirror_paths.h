// The hybrid method's rays (seed 002, chapter 6, taken past one bounce): from every pixel whose
// surface has a mirror-like lobe (smoothLobe: a polished coat, a metal, smooth glass), the
// reflected and refracted rays are traced with Embree on the CPU through further mirror-like
// lobes until they reach surfaces the frame's deferred passes can shade. Those surfaces become
// layers of secondary G-buffers, each pixel with the weight its light reaches the camera by
// (Fresnel of every interface on the way, glass tint); emitters and the sky met on the way are
// added here. Glossy lobes (shading::glossyLobe, up to a roughness) send rays sampled from their
// GGX distribution, one layer slot each; rougher lobes stay with the rasterized GGX highlight
// (docs/hybrid.md).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "shaders/shared/gbuffer.h"

namespace voxgi {

class RayTracer;

// One layer of secondary surfaces, a value per pixel in GL's row order (bottom row first): the
// four G-buffer targets as shaders/shared/gbuffer.h encodes them (position.w = 0 where the layer
// holds no surface), ready to upload.
struct SecondaryLayer {
    std::vector<glm::vec4> position, normal, albedo, emission;
    std::vector<glm::vec4> viewOrigin;           // xyz: the point the ray to the surface left
    std::vector<glm::vec4> weight;               // rgb: the surface's outgoing radiance times this reaches the pixel
    glm::ivec4 bounds{0};                        // the pixels holding surfaces: x, y, width, height
};

// The most rays a glossy pixel sends per frame.
constexpr int kMaxGlossyRays = 16;

struct MirrorPaths {
    int width = 0, height = 0;
    // Layer k holds, per pixel, the k-th shadeable surface found (the reflection's first).
    std::vector<SecondaryLayer> layers;
    // Emitters and sky met by the rays, times their weights: after one mirror-like scattering
    // (the path tracer's direct layer), and after more (its indirect layer).
    std::vector<glm::vec4> emittedDirect, emittedIndirect;
    glm::ivec4 emittedBounds{0};   // x, y, width, height: holds every traced pixel (emitted is 0 outside)
    std::size_t pixels = 0;        // pixels with a mirror-like lobe
    std::size_t glossyPixels = 0;  // pixels with a traced glossy lobe
    std::uint64_t rays = 0;
};

struct MirrorPathInput {
    int width = 0, height = 0;
    const float* position = nullptr;  // the G-buffer's position and normal texels, RGBA, GL row order
    const float* normal = nullptr;
    const float* albedo = nullptr;
    const float* emission = nullptr;
    glm::vec3 eye{0.0f};
    int depth = 3;           // mirror-like scatterings followed from the pixel's surface, at most
    std::uint32_t frame = 0; // seeds the glossy rays and the choice between reflection and refraction
    float glossyRoughness = 0.0f;  // glossy lobes up to this perceptual roughness are traced too
    int glossyRays = 1;            // per glossy pixel, at most kMaxGlossyRays
};

// Whether a decoded G-buffer surface has a mirror-like lobe the hybrid method traces.
bool tracesMirrorLobe(const shading::GBufferSurface& s);

MirrorPaths traceMirrorPaths(const RayTracer& tracer, const MirrorPathInput& input);

}  // namespace voxgi
