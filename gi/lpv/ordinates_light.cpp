#include "gi/lpv/ordinates_light.h"

#include <algorithm>
#include <chrono>
#include <string>

#include <tbb/parallel_for.h>

#include "gi/lpv/gl_cascade_uniforms.h"
#include "gi/lpv/tap_masks.h"
#include "gi/raytrace/ray_tracer.h"
#include "gi/raytrace/triangle_bvh.h"
#include "gi/raytrace/triangle_bvh_gl.h"
#include "gi/sky/sky_volume.h"
#include "shaders/lpv/limits.h"
#include "volumes/voxel_surfaces.h"

namespace voxgi {

namespace {
// lpv.tap_visibility, where there are triangles to trace.
TapVisibility tapsTested(const LpvDesc& desc, const Scene& scene) {
    return scene.triangleCount() > 0 ? desc.tapVisibility : TapVisibility::Off;
}

gl::Program::Defines applyDefines(TapVisibility taps) {
    if (taps == TapVisibility::Rays) return {{"LPV_TAP_VISIBILITY", "1"}};
    if (taps == TapVisibility::Cells) return {{"LPV_TAP_MASKS", "1"}};
    return {};
}
}  // namespace

OrdinatesLight::OrdinatesLight(const LpvDesc& desc, const Scene& scene)
    : desc_(desc),
      program_(gl::Program::graphics("frame/fullscreen.vert", "lpv/apply_ordinates.frag",
                                     applyDefines(tapsTested(desc, scene)))),
      scene_(scene) {
    if (desc_.backend == Backend::Gl) gl_ = std::make_unique<GlOrdinates>();
    if (tapsTested(desc, scene) == TapVisibility::Rays) {
        triangles_ = std::make_unique<TriangleBvhGl>(scene, buildTriangleBvh(scene));
        tapRayOffset_ = surfaceRayOffset(scene);
    }
    if (tapsTested(desc, scene) == TapVisibility::Cells) maskTracer_ = std::make_unique<RayTracer>(scene);
}

OrdinatesLight::~OrdinatesLight() = default;

bool OrdinatesLight::place(const std::vector<CascadePlacement>& placements, const SparseGeometryVolume* voxels) {
    const std::size_t count = placements.size();
    transports_.resize(count);
    ring_.resize(count);
    inner_.resize(count);
    carry_.resize(2 * count);
    std::vector<std::size_t> moved;
    for (std::size_t c = 0; c < count; ++c) {
        const CascadeGrid& g = placements[c].grid;
        const OrdinatesTransport* t = transports_[c].get();
        if (t && t->grid().origin == g.origin && t->grid().cellSize == g.cellSize && t->grid().resolution == g.resolution)
            continue;
        moved.push_back(c);
    }
    placements_ = placements;
    tbb::parallel_for(std::size_t(0), moved.size(), [&](std::size_t i) {
        const std::size_t c = moved[i];
        const CascadeGrid& g = placements[c].grid;
        auto t = std::make_unique<OrdinatesTransport>(g, desc_.ordinatesPerFace, ordinatesReach(desc_.applyNormalOffset));
        // Bricks where the voxelized surfaces are (the receivers); without them, or dense, all.
        if (!desc_.sparse || !voxels || int(c) >= voxels->levelCount()) t->allocateAllBricks();
        if (voxels && int(c) < voxels->levelCount()) {
            IndexBox box;
            box.min = g.origin;
            box.max = g.origin + glm::ivec3(g.resolution - 1);
            std::vector<OrdinateSurface> surfaces;
            forEachVoxelSurface(*voxels, int(c), box, [&](const VoxelSurfaceArea& s) {
                surfaces.push_back({s.voxel - g.origin, s.coverage, s.vectorCoverage, s.albedo, s.projectedCoverage});
            });
            t->addSurfaces(surfaces);
        }
        transports_[c] = std::move(t);
        carry_[2 * c].clear();
        carry_[2 * c + 1].clear();
    });
    return !moved.empty();
}

void OrdinatesLight::clearSources() {
    for (std::size_t c = 0; c < transports_.size(); ++c) {
        ring_[c] = transports_[c]->emptySources();
        inner_[c] = transports_[c]->emptySources();
    }
}

void OrdinatesLight::addSurfels(const SurfelSource& surfels) {
    if (transports_.empty()) return;
    // Chunks of surfels: each one's bin shares once (every cascade has the same bins), then every
    // cascade adds the chunk's ring and inner shares (its own sources: one task each).
    const std::vector<OrdinateBin>& bins = transports_[0]->bins();
    const std::size_t nb = bins.size(), chunk = 16384;
    std::vector<float> shares;
    for (std::size_t first = 0; first < surfels.surfels.size(); first += chunk) {
        const std::size_t count = std::min(chunk, surfels.surfels.size() - first);
        shares.assign(count * nb, 0.0f);
        tbb::parallel_for(std::size_t(0), count, [&](std::size_t i) {
            const Surfel& s = surfels.surfels[first + i];
            if (s.flux == glm::vec3(0.0f)) return;
            emissionShares(bins, s.normal, shares.data() + i * nb);
        });
        tbb::parallel_for(std::size_t(0), transports_.size(), [&](std::size_t c) {
            for (std::size_t i = 0; i < count; ++i) {
                const Surfel& s = surfels.surfels[first + i];
                if (s.flux == glm::vec3(0.0f)) continue;
                const SourceShares split = sourceShares(placements_, c, s.position);
                const float* sh = shares.data() + i * nb;
                if (split.ring > 0.0f)
                    transports_[c]->addFlux(s.position, s.normal, s.flux * split.ring, sh, desc_.injectNormalOffset, ring_[c]);
                if (c > 0 && split.inner > 0.0f)
                    transports_[c]->addFlux(s.position, s.normal, s.flux * split.inner, sh, desc_.injectNormalOffset,
                                            inner_[c]);
            }
        });
    }
}

void OrdinatesLight::addSkyBounce(const SkyVolume& sky) {
    tbb::parallel_for(std::size_t(0), transports_.size(), [&](std::size_t c) {
        auto irradiance = [&](glm::vec3 p, glm::vec3 n) { return sky.sampleIrradiance(p, n); };
        transports_[c]->addReflectedIrradiance(
            irradiance, [&](glm::vec3 x) { return sourceShares(placements_, c, x).ring; }, ring_[c]);
        if (c > 0)
            transports_[c]->addReflectedIrradiance(
                irradiance, [&](glm::vec3 x) { return sourceShares(placements_, c, x).inner; }, inner_[c]);
    });
}

void OrdinatesLight::solve() {
    stats_ = {};
    if (maskTracer_) updateTapMasks();  // timed apart: only when a cascade moved
    const auto t0 = std::chrono::steady_clock::now();
    // Fitted: every bounce now; a number of sweeps continues from the last update's reflections.
    const bool incremental = desc_.bounces && desc_.sweeps != kFittedInteger;
    const int maxBounces = !desc_.bounces ? 1 : incremental ? desc_.sweeps : 256;
    layOutPool();
    constexpr std::size_t kSlotBytes = BrickMap::kSlotValues * sizeof(glm::vec4);
    for (std::size_t c = 0; c < transports_.size(); ++c) {
        for (int set = 0; set < 2; ++set) {
            const OrdinatesTransport::Sources& sources = set == 0 ? ring_[c] : inner_[c];
            const std::size_t first = firstSlot_[2 * c + std::size_t(set)];
            if (gl_) {
                // The sweeps write the pool.
                const int sweeps = gl_->solve(*transports_[c], sources, desc_.occlusion, maxBounces, pool_.id(), first);
                stats_.sweeps = std::max(stats_.sweeps, sweeps);
                continue;
            }
            const std::size_t slots = transports_[c]->bricks().slots();
            if (set == 1 && sources.watts <= 0.0) {
                if (slots > 0)
                    glClearNamedBufferSubData(pool_.id(), GL_R32F, GLintptr(first * kSlotBytes), GLsizeiptr(slots * kSlotBytes),
                                              GL_RED, GL_FLOAT, nullptr);
                continue;
            }
            std::vector<glm::vec3>* carry = incremental ? &carry_[2 * c + std::size_t(set)] : nullptr;
            const IrradianceBricks cube = transports_[c]->solve(sources, desc_.occlusion, maxBounces, carry);
            const OrdinatesStats& st = transports_[c]->stats();
            stats_.sweeps = std::max(stats_.sweeps, st.sweeps);
            if (incremental) {
                stats_.leftWatts += st.leftWatts;
                if (st.leftWatts >= kOrdinatesConverged * st.emittedWatts) stats_.converged = false;
            }
            // The CPU keeps no copy: irradiance() reads the pool back.
            if (!cube.empty())
                glNamedBufferSubData(pool_.id(), GLintptr(first * kSlotBytes), GLsizeiptr(cube.size() * sizeof(glm::vec4)),
                                     cube.data());
        }
        stats_.emittedWatts += ring_[c].watts;
        stats_.surfaceCells += transports_[c]->surfaceCells();
    }
    if (!ring_.empty()) stats_.outsideWatts = ring_.back().outsideWatts;
    stats_.solveMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

void OrdinatesLight::layOutPool() {
    const std::size_t count = transports_.size();
    firstSlot_.assign(2 * count, 0);
    tableStart_.assign(count, 0);
    std::size_t slots = 0, tables = 0;
    bool changed = tableRevisions_.size() != count;
    tableRevisions_.resize(count, 0);
    stats_.bricks = stats_.gridBricks = 0;
    for (std::size_t c = 0; c < count; ++c) {
        const BrickMap& b = transports_[c]->bricks();
        firstSlot_[2 * c] = slots;
        firstSlot_[2 * c + 1] = slots + b.slots();
        slots += 2 * b.slots();
        tableStart_[c] = int(tables);
        tables += b.tableSize();
        if (tableRevisions_[c] != transports_[c]->geometryRevision()) changed = true;
        stats_.bricks += b.slots();
        stats_.gridBricks += b.tableSize();
    }
    stats_.poolBytes = slots * BrickMap::kSlotValues * sizeof(glm::vec4);
    // Exactly the slots: the pool is the largest buffer, and grows only when a surface appears.
    gl::ensureBuffer(pool_, poolCap_, stats_.poolBytes, 1.0);
    if (!changed && tables_) return;
    std::vector<int> all;
    all.reserve(tables);
    for (std::size_t c = 0; c < count; ++c) {
        const std::vector<int>& t = transports_[c]->bricks().table();
        all.insert(all.end(), t.begin(), t.end());
        tableRevisions_[c] = transports_[c]->geometryRevision();
    }
    gl::ensureBuffer(tables_, tablesCap_, all.size() * sizeof(int));
    if (!all.empty()) glNamedBufferSubData(tables_.id(), 0, GLsizeiptr(all.size() * sizeof(int)), all.data());
}

void OrdinatesLight::updateTapMasks() {
    const std::size_t count = transports_.size();
    masks_.resize(count);
    maskRevisions_.resize(count, 0);
    std::vector<std::size_t> stale;
    for (std::size_t c = 0; c < count; ++c)
        if (masks_[c].cells.empty() || maskRevisions_[c] != transports_[c]->geometryRevision()) stale.push_back(c);
    if (stale.empty() && masksBuffer_) return;
    const auto t0 = std::chrono::steady_clock::now();
    // The cascades side by side (each samples its points on one thread, then traces in parallel).
    tbb::parallel_for(std::size_t(0), stale.size(), [&](std::size_t i) {
        const std::size_t c = stale[i];
        masks_[c] = traceTapMasks(scene_, *maskTracer_, transports_[c]->grid(), transports_[c]->bricks());
        maskRevisions_[c] = transports_[c]->geometryRevision();
    });
    std::vector<std::uint32_t> all;
    maskBase_.assign(count, 0);
    std::size_t masked = 0;  // surface cells of the cascades before
    for (std::size_t c = 0; c < count; ++c) {
        maskBase_[c] = int(all.size());
        for (std::int32_t first : masks_[c].cells)
            all.push_back(first < 0 ? 0xFFFFFFFFu : std::uint32_t(masked + std::size_t(first)));
        masked += masks_[c].masks.size() / kTapMasksPerCell;
    }
    masksStart_ = int(all.size());
    for (std::size_t c = 0; c < count; ++c) all.insert(all.end(), masks_[c].masks.begin(), masks_[c].masks.end());
    all.resize(std::max<std::size_t>(all.size(), 1), kAllTapBits);
    gl::ensureBuffer(masksBuffer_, masksCap_, all.size() * sizeof(std::uint32_t), 1.0);
    glNamedBufferSubData(masksBuffer_.id(), 0, GLsizeiptr(all.size() * sizeof(std::uint32_t)), all.data());
    stats_.tapMasksMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

IrradianceBricks OrdinatesLight::irradiance(std::size_t c) const {
    const std::size_t slots = transports_.at(c)->bricks().slots();
    IrradianceBricks sum = readBricks(pool_.id(), firstSlot_.at(2 * c), slots),
                     inner = readBricks(pool_.id(), firstSlot_.at(2 * c + 1), slots);
    for (std::size_t i = 0; i < sum.size() && i < inner.size(); ++i) sum[i] += inner[i];
    return sum;
}

void OrdinatesLight::apply(const GBufferView& g) const {
    program_.use();
    bindGBufferTextures(program_, g);
    program_.set("uCascadeCount", int(placements_.size()));
    program_.set("uApplyNormalOffset", desc_.applyNormalOffset);
    program_.set("uQuadraticRead", desc_.cubeRead == CubeRead::Quadratic ? 1 : 0);
    program_.set("uResolution", desc_.resolution);
    if (triangles_) {
        triangles_->bind(program_, 14);
        program_.set("uTapRayOffset", tapRayOffset_);
    }
    if (maskTracer_) {
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 15, masksBuffer_.id());
        program_.set("uMasksStart", masksStart_);
    }
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 12, pool_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 13, tables_.id());
    program_.set("uEye", g.eye);
    program_.set("uGlossy", desc_.glossy ? 1 : 0);
    setCascadeUniforms(program_, placements_);
    for (std::size_t c = 0; c < std::size_t(kLpvMaxCascades); ++c) {
        const std::string idx = "[" + std::to_string(c) + "]";
        const bool used = c < placements_.size();
        if (!used) continue;
        const BrickMap& b = transports_[c]->bricks();
        program_.set(("uCellSize" + idx).c_str(), placements_[c].grid.cellSize);
        program_.set(("uTableSide" + idx).c_str(), b.tableSide());
        program_.set(("uTableStart" + idx).c_str(), tableStart_[c]);
        program_.set(("uRingSlot" + idx).c_str(), int(firstSlot_[2 * c]));
        program_.set(("uInnerSlot" + idx).c_str(), int(firstSlot_[2 * c + 1]));
        program_.set(("uSlots" + idx).c_str(), int(b.slots()));
        if (maskTracer_) program_.set(("uMaskBase" + idx).c_str(), maskBase_[c]);
    }
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

}  // namespace voxgi
