// The sky-lighting volume (seed 002 section 5.3; the sky issue's item 2): irradiance from the
// sky, with the scene's own occlusion, as 3-band SH (9 coefficients per colour) at the centres
// of a grid of cells over the scene. Each cell traces `rays` spherical-Fibonacci directions with
// Embree against the real triangles; a ray that leaves the scene brings the sky's radiance in
// its direction (Sky::radianceAt), one that hits a back face counts toward the cell being inside
// solid geometry (then it holds nothing). The frame's sky_light pass lights every G-buffer
// surface with it (shaders/frame/sky_light.frag); sampleIrradiance is the same lookup on the CPU.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "gi/settings_table.h"
#include "scenes/scene.h"

namespace voxgi {

class RayTracer;

struct SkyVolumeDesc {
    bool light = true;    // the frame's sky_light pass (false: surfaces get no light from the sky)
    int resolution = 32;  // cells along the scene's longest side (the others in proportion)
    int rays = 128;       // per cell
};
const SettingsTable<SkyVolumeDesc>& skyVolumeSettings();
SkyVolumeDesc readSkyVolumeDesc(const GiSettings& gi);

class SkyVolume {
public:
    // Sizes the grid (nothing traced yet); `tracer` (and its scene) must outlive the volume.
    SkyVolume(const RayTracer& tracer, const SkyVolumeDesc& desc);

    // Traces cells until all are done or `budgetMs` has passed (at least one batch of 32 cells
    // per call; a budget of 0 or less does every cell). Returns true once the volume is complete. The sky
    // or the geometry changing is a new volume.
    bool update(double budgetMs = 0.0);
    bool complete() const { return next_ == cellCount(); }

    glm::ivec3 dims() const { return dims_; }
    glm::vec3 origin() const { return origin_; }  // centre of cell (0, 0, 0)
    float cellSize() const { return cellSize_; }
    std::size_t cellCount() const { return std::size_t(dims_.x) * std::size_t(dims_.y) * std::size_t(dims_.z); }
    std::size_t index(glm::ivec3 c) const {
        return (std::size_t(c.z) * std::size_t(dims_.y) + std::size_t(c.y)) * std::size_t(dims_.x) + std::size_t(c.x);
    }

    // Per cell: irradiance SH (E_lm = A_l L_lm, gi/sh/sh.h order) for r, g, b, then validity.
    // Packed as 7 vec4 per cell, the GPU layout: coefficients 0..26 (colour-major: r0..r8,
    // g0..g8, b0..b8) and the 28th float 1 for a cell in open space, 0 inside geometry or not
    // traced yet.
    static constexpr int kVec4PerCell = 7;
    const std::vector<glm::vec4>& packed() const { return packed_; }

    // Irradiance (W/m^2) on a surface at p with unit normal n: the cells around p + n * cell/2,
    // trilinear, weighted by validity.
    glm::vec3 sampleIrradiance(glm::vec3 p, glm::vec3 n) const;

    double buildMs() const { return buildMs_; }  // the time update() has spent in all

private:
    void traceCell(std::size_t cell);

    const RayTracer& tracer_;
    const Scene& scene_;
    SkyVolumeDesc desc_;
    glm::ivec3 dims_{0};
    glm::vec3 origin_{0.0f};
    float cellSize_ = 1.0f;
    std::vector<glm::vec3> directions_;
    std::vector<glm::vec4> packed_;
    std::size_t next_ = 0;
    double buildMs_ = 0.0;
};

}  // namespace voxgi
