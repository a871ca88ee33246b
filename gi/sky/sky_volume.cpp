#include "gi/sky/sky_volume.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <tbb/parallel_for.h>

#include "gi/raytrace/ray_tracer.h"
#include "gi/sampling/sequences.h"
#include "gi/sh/sh.h"
#include "scenes/memory_limit.h"
#include "shaders/shared/sky_volume.h"

namespace voxgi {

const SettingsTable<SkyVolumeDesc>& skyVolumeSettings() {
    static const SettingsTable<SkyVolumeDesc> table = [] {
        using D = SkyVolumeDesc;
        SettingsTable<D> t("sky");
        t.flag("light", &D::light, "the frame lights surfaces with the sky-lighting volume (sky_light pass)");
        t.integer("resolution", &D::resolution, 2, 512, "sky-lighting volume: cells along the scene's longest side");
        t.integer("rays", &D::rays, 8, 4096, "sky-lighting volume: rays per cell");
        t.number("update_ms", &D::updateMs, 0.0, 1000.0,
                 "sky-lighting volume: CPU ms a frame for tracing it again after the sky changes (0: whole at once)");
        return t;
    }();
    return table;
}

SkyVolumeDesc readSkyVolumeDesc(const GiSettings& gi) { return skyVolumeSettings().read(gi); }

SkyVolume::SkyVolume(const RayTracer& tracer, const SkyVolumeDesc& desc)
    : tracer_(tracer), scene_(tracer.scene()), desc_(desc), skyRevision_(tracer.scene().sky.revision) {
    const Bounds b = scene_.bounds();
    const glm::vec3 extent = b.valid() ? b.extent() : glm::vec3(1.0f);
    cellSize_ = std::max(std::max(extent.x, std::max(extent.y, extent.z)), 1e-6f) / float(desc.resolution);
    // Cell centres from the low corner to the high one, so every surface lies between centres.
    dims_ = glm::ivec3(glm::ceil(extent / cellSize_)) + 1;
    origin_ = (b.valid() ? b.min : glm::vec3(0.0f)) - 0.5f * (glm::vec3(dims_ - 1) * cellSize_ - extent);
    brickDims_ = (dims_ + kBrickCells - 1) / kBrickCells;
    for (int i = 0; i < desc.rays; ++i) directions_.push_back(sphericalFibonacci(i, desc.rays));
    markBricks();
    const glm::ivec3 atlas = atlasSize();
    const double texels = double(atlas.x) * double(atlas.y) * double(atlas.z);
    requireMemory(texels * double(sizeof(glm::vec4)) + double(brickSlot_.size()) * double(sizeof(std::int32_t)),
                  "the sky-lighting volume (" + std::to_string(bricks_.size()) + " bricks of " +
                      std::to_string(kCellsPerBrick) + " cells at sky.resolution=" + std::to_string(desc.resolution) + ")");
    packed_.assign(std::size_t(texels), glm::vec4(0.0f));
}

void SkyVolume::markBricks() {
    // A surface point p's lookup (sampleIrradiance) reads the 8 cells around p + n * cell / 2,
    // which lie within floor(g - 1/2) .. floor(g + 1/2) + 1 of p's grid coordinate g. Points
    // over every triangle no farther apart than half a cell mark the bricks of those cells.
    const std::size_t brickCount = std::size_t(brickDims_.x) * std::size_t(brickDims_.y) * std::size_t(brickDims_.z);
    std::vector<char> marked(brickCount, 0);
    auto markPoint = [&](glm::vec3 p) {
        const glm::vec3 g = (p - origin_) / cellSize_;
        const glm::ivec3 lo = glm::clamp(glm::ivec3(glm::floor(g - 0.5f)), glm::ivec3(0), dims_ - 1);
        const glm::ivec3 hi = glm::clamp(glm::ivec3(glm::floor(g + 0.5f)) + 1, glm::ivec3(0), dims_ - 1);
        const glm::ivec3 blo = lo / kBrickCells, bhi = hi / kBrickCells;
        for (int z = blo.z; z <= bhi.z; ++z)
            for (int y = blo.y; y <= bhi.y; ++y)
                for (int x = blo.x; x <= bhi.x; ++x)
                    marked[(std::size_t(z) * std::size_t(brickDims_.y) + std::size_t(y)) * std::size_t(brickDims_.x) +
                           std::size_t(x)] = 1;
    };
    for (const Mesh& mesh : scene_.meshes)
        for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
            const glm::vec3 a = mesh.positions[mesh.indices[3 * t]], b = mesh.positions[mesh.indices[3 * t + 1]],
                            c = mesh.positions[mesh.indices[3 * t + 2]];
            const float longest = std::max(glm::length(b - a), std::max(glm::length(c - b), glm::length(a - c)));
            if (!std::isfinite(longest)) continue;  // renderers skip such triangles
            const int steps = std::max(1, int(std::ceil(longest / (0.5f * cellSize_))));
            for (int i = 0; i <= steps; ++i)
                for (int j = 0; i + j <= steps; ++j)
                    markPoint(a + (b - a) * (float(i) / float(steps)) + (c - a) * (float(j) / float(steps)));
        }
    brickSlot_.assign(brickCount, -1);
    for (std::size_t i = 0; i < brickCount; ++i) {
        if (!marked[i]) continue;
        brickSlot_[i] = std::int32_t(bricks_.size());
        bricks_.push_back(glm::ivec3(int(i % std::size_t(brickDims_.x)), int(i / std::size_t(brickDims_.x) % std::size_t(brickDims_.y)),
                                     int(i / (std::size_t(brickDims_.x) * std::size_t(brickDims_.y)))));
    }
    // Columns for an atlas about as wide (7 texels a cell) as it is deep.
    atlasColumns_ = std::max(1, int(std::ceil(std::sqrt(double(bricks_.size()) / 7.0))));
}

std::unique_ptr<SkyVolume> SkyVolume::sameBricks() const {
    requireMemory(double(packed_.size()) * double(sizeof(glm::vec4)), "the sky-lighting volume traced again");
    std::unique_ptr<SkyVolume> v(new SkyVolume(*this));
    std::fill(v->packed_.begin(), v->packed_.end(), glm::vec4(0.0f));
    v->next_ = 0;
    v->buildMs_ = 0.0;
    v->skyRevision_ = scene_.sky.revision;
    return v;
}

glm::ivec3 SkyVolume::atlasSize() const {
    const int rows = std::max(1, int((bricks_.size() + std::size_t(atlasColumns_) - 1) / std::size_t(atlasColumns_)));
    return {kVec4PerCell * kBrickCells * atlasColumns_, kBrickCells, kBrickCells * rows};
}

std::size_t SkyVolume::atlasIndex(int slot, glm::ivec3 local) const {
    const glm::ivec3 size = atlasSize();
    const int x = kVec4PerCell * (kBrickCells * (slot % atlasColumns_) + local.x);
    const int z = kBrickCells * (slot / atlasColumns_) + local.z;
    return (std::size_t(z) * std::size_t(size.y) + std::size_t(local.y)) * std::size_t(size.x) + std::size_t(x);
}

const glm::vec4* SkyVolume::cell(glm::ivec3 c) const {
    if (glm::any(glm::lessThan(c, glm::ivec3(0))) || glm::any(glm::greaterThanEqual(c, dims_))) return nullptr;
    const glm::ivec3 brick = c / kBrickCells;
    const std::int32_t slot =
        brickSlot_[(std::size_t(brick.z) * std::size_t(brickDims_.y) + std::size_t(brick.y)) * std::size_t(brickDims_.x) +
                   std::size_t(brick.x)];
    return slot < 0 ? nullptr : &packed_[atlasIndex(slot, c - brick * kBrickCells)];
}

void SkyVolume::traceCell(std::size_t work) {
    const int slot = int(work / kCellsPerBrick);
    const int local = int(work % kCellsPerBrick);
    const glm::ivec3 l(local % kBrickCells, local / kBrickCells % kBrickCells, local / (kBrickCells * kBrickCells));
    const glm::ivec3 c = bricks_[std::size_t(slot)] * kBrickCells + l;
    if (glm::any(glm::greaterThanEqual(c, dims_))) return;  // past the grid's edge: stays invalid
    const glm::vec3 p = origin_ + glm::vec3(c) * cellSize_;
    std::vector<RayHit> hits(directions_.size());
    tracer_.intersectFan(p, directions_.data(), int(directions_.size()), hits.data());
    // Radiance SH of what the cell sees of the sky, by Monte Carlo over the uniform directions.
    float coefficients[3][9] = {};
    int backfaces = 0;
    const float weight = 4.0f * shading::kPi / float(directions_.size());
    for (std::size_t i = 0; i < directions_.size(); ++i) {
        if (hits[i].hit) {
            backfaces += hits[i].frontFace ? 0 : 1;
            continue;
        }
        const glm::vec3 l = scene_.sky.radianceAt(directions_[i]) * weight;
        const sh::Sh9 y = sh::basis9(directions_[i]);
        for (int k = 0; k < 9; ++k)
            for (int col = 0; col < 3; ++col) coefficients[col][k] += l[col] * y.c[std::size_t(k)];
    }
    // Inside closed geometry: most rays see the inside of some surface.
    const bool open = float(backfaces) <= 0.25f * float(directions_.size());
    const float lobe[9] = {sh::kCosLobe0, sh::kCosLobe1, sh::kCosLobe1, sh::kCosLobe1, sh::kCosLobe2,
                           sh::kCosLobe2, sh::kCosLobe2, sh::kCosLobe2, sh::kCosLobe2};
    float flat[28] = {};
    for (int col = 0; col < 3; ++col)
        for (int k = 0; k < 9; ++k) flat[col * 9 + k] = open ? lobe[k] * coefficients[col][k] : 0.0f;
    flat[27] = open ? 1.0f : 0.0f;
    const std::size_t at = atlasIndex(slot, l);
    for (int v = 0; v < kVec4PerCell; ++v)
        packed_[at + std::size_t(v)] = glm::vec4(flat[4 * v], flat[4 * v + 1], flat[4 * v + 2], flat[4 * v + 3]);
}

bool SkyVolume::update(double budgetMs) {
    const auto start = std::chrono::steady_clock::now();
    // Batches of cells in parallel while another batch, as long as the last one, still fits in
    // the budget: 32 cells of 128 rays are about a millisecond on 2 cores, so a budget of a few
    // milliseconds is kept unless one batch alone exceeds it.
    constexpr std::size_t kBatch = 32;
    double lastBatchMs = 0.0;
    while (!complete()) {
        const auto batchStart = std::chrono::steady_clock::now();
        const std::size_t end = std::min(tracedCells(), next_ + kBatch);
        tbb::parallel_for(next_, end, [&](std::size_t cell) { traceCell(cell); });
        next_ = end;
        const auto now = std::chrono::steady_clock::now();
        lastBatchMs = std::chrono::duration<double, std::milli>(now - batchStart).count();
        const double ms = std::chrono::duration<double, std::milli>(now - start).count();
        if (budgetMs > 0.0 && ms + lastBatchMs > budgetMs) break;
    }
    buildMs_ += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return complete();
}

glm::vec3 SkyVolume::sampleIrradiance(glm::vec3 p, glm::vec3 n) const {
    const shading::SkyVolumeTaps t = shading::skyVolumeTaps(p + n * (0.5f * cellSize_), origin_, cellSize_);
    glm::vec3 sum(0.0f);
    float weights = 0.0f;
    for (int corner = 0; corner < 8; ++corner) {
        const glm::ivec3 o(corner & 1, (corner >> 1) & 1, corner >> 2);
        const glm::vec4* v = cell(glm::clamp(t.base + o, glm::ivec3(0), dims_ - 1));
        if (!v) continue;
        const glm::vec3 w3 = glm::mix(glm::vec3(1.0f) - t.fraction, t.fraction, glm::vec3(o));
        const float w = w3.x * w3.y * w3.z * v[6].w;
        if (!(w > 0.0f)) continue;
        sum += w * shading::skyCellIrradiance(v[0], v[1], v[2], v[3], v[4], v[5], v[6], n);
        weights += w;
    }
    return weights > 0.0f ? sum / weights : glm::vec3(0.0f);
}

}  // namespace voxgi
