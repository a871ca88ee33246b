// The sky-lighting volume (seed 002 section 5.3; the sky issue's item 2): irradiance from the
// sky, with the scene's own occlusion, as 3-band SH (9 coefficients per colour) at the centres
// of a grid of cells over the scene, stored sparsely: only the bricks of 4^3 cells that a
// surface's lookup can reach (cells within one and a half cells of a triangle) are traced and
// kept; a lookup elsewhere finds no cell, as it finds none inside solid geometry. Each cell
// traces `rays` spherical-Fibonacci directions with
// Embree against the real triangles; a ray that leaves the scene brings the sky's radiance in
// its direction (Sky::radianceAt), one that hits a back face counts toward the cell being inside
// solid geometry (then it holds nothing). The frame's sky_light pass lights every G-buffer
// surface with it (shaders/frame/sky_light.comp); sampleIrradiance is the same lookup on the CPU.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "gi/settings_table.h"
#include "shaders/shared/sky_volume.h"
#include "scenes/scene.h"

namespace voxgi {

class RayTracer;

struct SkyVolumeDesc {
    bool light = true;    // the frame's sky_light pass (false: surfaces get no light from the sky)
    int resolution = 32;  // cells along the scene's longest side (the others in proportion)
    int rays = 128;       // per cell
    // After the sky changes (the viewer moves the atmosphere's sun), the volume is traced again
    // over frames, this many CPU milliseconds a frame (the sky issue's per-frame budget), and
    // the old one lights the frames until the new one is whole. The first build is whole.
    float updateMs = 2.0f;
};
const SettingsTable<SkyVolumeDesc>& skyVolumeSettings();
SkyVolumeDesc readSkyVolumeDesc(const GiSettings& gi);

class SkyVolume {
public:
    // Sizes the grid (nothing traced yet); `tracer` (and its scene) must outlive the volume.
    SkyVolume(const RayTracer& tracer, const SkyVolumeDesc& desc);

    // Traces cells until all are done or another batch, as long as the last, would pass
    // `budgetMs` (at least one batch of 32 cells per call; a budget of 0 or less does every
    // cell). Returns true once the volume is complete. The sky changing is a new volume
    // (sameBricks), the geometry changing one made anew.
    bool update(double budgetMs = 0.0);
    bool complete() const { return next_ == tracedCells(); }
    // A volume over the same bricks with nothing traced yet, for the scene's sky as it is now:
    // the sky changed, the geometry did not.
    std::unique_ptr<SkyVolume> sameBricks() const;
    // The scene's sky.revision when this volume was made: the sky its cells hold.
    int skyRevision() const { return skyRevision_; }
    const SkyVolumeDesc& desc() const { return desc_; }

    glm::ivec3 dims() const { return dims_; }     // the whole grid, cells
    glm::vec3 origin() const { return origin_; }  // centre of cell (0, 0, 0)
    float cellSize() const { return cellSize_; }
    std::size_t gridCells() const { return std::size_t(dims_.x) * std::size_t(dims_.y) * std::size_t(dims_.z); }

    // Bricks: kBrickCells^3 cells, brickDims() of them over the grid, each empty or stored.
    static constexpr int kBrickCells = shading::kSkyBrickCells;
    glm::ivec3 brickDims() const { return brickDims_; }
    std::size_t activeBricks() const { return bricks_.size(); }
    std::size_t tracedCells() const { return bricks_.size() * kCellsPerBrick; }
    // The slot of every brick (x fastest), -1 where it is empty: the GPU's index texture.
    const std::vector<std::int32_t>& brickSlots() const { return brickSlot_; }
    // Stored bricks side by side in an atlas of atlasColumns() x atlasRows() bricks (slot s at
    // column s % columns, row s / columns): atlasSize() vec4 texels, x fastest, 7 per cell along x.
    int atlasColumns() const { return atlasColumns_; }
    glm::ivec3 atlasSize() const;

    // Per cell: irradiance SH (E_lm = A_l L_lm, gi/sh/sh.h order) for r, g, b, then validity.
    // Packed as 7 vec4 per cell, the GPU layout: coefficients 0..26 (colour-major: r0..r8,
    // g0..g8, b0..b8) and the 28th float 1 for a cell in open space, 0 inside geometry, outside
    // the stored bricks or not traced yet. The atlas, as the GPU reads it.
    static constexpr int kVec4PerCell = 7;
    const std::vector<glm::vec4>& packed() const { return packed_; }
    // A cell's 7 vec4, null when its brick is empty or it lies outside the grid.
    const glm::vec4* cell(glm::ivec3 c) const;

    // Irradiance (W/m^2) on a surface at p with unit normal n: the cells around p + n * cell/2,
    // trilinear, weighted by validity.
    glm::vec3 sampleIrradiance(glm::vec3 p, glm::vec3 n) const;

    double buildMs() const { return buildMs_; }  // the time update() has spent in all

private:
    SkyVolume(const SkyVolume&) = default;  // sameBricks
    static constexpr std::size_t kCellsPerBrick = std::size_t(kBrickCells) * kBrickCells * kBrickCells;
    void markBricks();
    void traceCell(std::size_t work);
    std::size_t atlasIndex(int slot, glm::ivec3 local) const;

    const RayTracer& tracer_;
    const Scene& scene_;
    SkyVolumeDesc desc_;
    glm::ivec3 dims_{0}, brickDims_{0};
    glm::vec3 origin_{0.0f};
    float cellSize_ = 1.0f;
    std::vector<std::int32_t> brickSlot_;
    std::vector<glm::ivec3> bricks_;  // by slot: the brick's coordinates
    int atlasColumns_ = 1;
    std::vector<glm::vec3> directions_;
    std::vector<glm::vec4> packed_;
    std::size_t next_ = 0;
    double buildMs_ = 0.0;
    int skyRevision_ = 0;
};

}  // namespace voxgi
