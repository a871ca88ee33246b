// The reference renderer: an unbiased path tracer on Embree (gi/raytrace) with next-event
// estimation and multiple importance sampling, Russian roulette, progressive accumulation and
// AOVs. Deterministic: pixel (x, y), sample s always draws the same random numbers, so the
// image depends on the seed and the sample count only, not on the thread count.
#pragma once

#include <cstdint>
#include <memory>

#include <glm/glm.hpp>

#include "gi/raytrace/ray_tracer.h"
#include "scenes/image.h"
#include "scenes/scene.h"

namespace voxgi {

// Changes whenever what the path tracer converges to changes (a bias fixed, a shading
// convention): cached references are keyed by it (tools/eval_run.cpp). 2: shadow segments that
// miss the light's own plane; 3: the shading normal alone decides what is above a surface;
// 4: a directional light's angular_diameter (the atmosphere's sun: a 0.53 degree disc).
constexpr int kPathTracerRevision = 4;

struct PathTracerOptions {
    int maxBounces = 0;         // scattering events per path; 0 = unlimited (roulette ends paths)
    std::uint64_t seed = 0;
    int width = 0;              // 0 = the scene camera's resolution
    int height = 0;
    // Light subpaths and connections (gi/pathtrace/light_paths.h) for the light of point and
    // spot lights and emitters; false: unidirectional paths only (the same image in
    // expectation, noisier).
    bool lightPaths = true;
    // false: leave out caustics, the light that reaches a diffuse surface by way of a specular
    // reflection or a refraction: past the first surface of a path that has a diffuse lobe,
    // surfaces scatter only their diffuse lobe (metals and glass then end the path), and no
    // light subpaths are traced. What methods that carry light between diffuse surfaces and
    // trace only what the camera sees in mirrors aim at (hybrid); not the physical image
    // (docs/reference.md).
    bool caustics = true;
};

// What one camera path brought back, split the way the AOVs are.
struct PathSample {
    glm::vec3 direct{0.0f};     // emitters and sky seen directly, plus light after one scattering
    glm::vec3 indirect{0.0f};   // light after two or more scatterings
    glm::vec3 albedo{0.0f};     // first hit (zero for background)
    glm::vec3 normal{0.0f};     // first hit's shading normal, turned towards the camera
    float depth = 0.0f;         // distance along the camera ray to the first hit (0 = none)
    int scatterings = 0;        // scattering events the path made before it ended
    std::uint32_t rays = 0;     // rays traced for this sample (camera, extension, shadow)
    glm::vec3 beauty() const { return direct + indirect; }
};

class PathTracer {
public:
    // Quad lights are traced through their emitting geometry; a scene built in code without
    // Scene::addQuadLightGeometry gets it added to a private copy.
    PathTracer(const Scene& scene, const PathTracerOptions& options);
    ~PathTracer();
    PathTracer(const PathTracer&) = delete;
    PathTracer& operator=(const PathTracer&) = delete;

    // Adds `samples` more samples per pixel (TBB over tiles).
    void render(int samples);
    // The average so far: beauty, direct, indirect, albedo, normal, depth (1 channel).
    Image image() const;

    int width() const;
    int height() const;
    int samplesPerPixel() const;
    std::uint64_t raysTraced() const;
    // Samples that came out NaN or infinite, dropped before they reached the image.
    std::uint64_t droppedSamples() const;

    // The path render() traces for pixel (x, y), sample `index` (box filter over the pixel),
    // with the light subpaths of that index (traced again unless one of the last few indices
    // asked for: callers going through many indices take them one at a time). Its camera ray
    // goes through Embree alone, where render() traces a tile's camera rays as one coherent
    // stream: the same path, unless Embree's SIMD rounding finds another triangle at an edge.
    PathSample samplePixel(int x, int y, std::uint64_t index) const;
    // The Embree scene the paths are traced in (benchmarks log and replay its rays).
    const RayTracer& rayTracer() const;
    // A unidirectional path along any ray; `stream` keys its random numbers.
    PathSample trace(glm::vec3 origin, glm::vec3 direction, std::uint64_t stream) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace voxgi
