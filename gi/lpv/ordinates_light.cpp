#include "gi/lpv/ordinates_light.h"

#include <algorithm>
#include <chrono>
#include <string>

#include <tbb/parallel_for.h>

#include "gi/lpv/gl_cascade_uniforms.h"
#include "shaders/lpv/limits.h"
#include "gi/sky/sky_volume.h"
#include "volumes/voxel_surfaces.h"

namespace voxgi {

OrdinatesLight::OrdinatesLight(const LpvDesc& desc)
    : desc_(desc), program_(gl::Program::graphics("frame/fullscreen.vert", "lpv/apply_ordinates.frag")) {
    if (desc_.backend == Backend::Gl) gl_ = std::make_unique<GlOrdinates>();
}

bool OrdinatesLight::place(const std::vector<CascadePlacement>& placements, const SparseGeometryVolume* voxels) {
    const std::size_t count = placements.size();
    transports_.resize(count);
    ring_.resize(count);
    inner_.resize(count);
    cubes_.resize(2 * count);
    carry_.resize(2 * count);
    const int n = desc_.resolution;
    while (textures_.size() < 2 * count) textures_.push_back(gl::createTexture(GL_TEXTURE_3D, GL_RGBA32F, n, n, kOrdinateFaces * n));
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
        auto t = std::make_unique<OrdinatesTransport>(g, desc_.ordinatesPerFace);
        if (voxels && int(c) < voxels->levelCount()) {
            IndexBox box;
            box.min = g.origin;
            box.max = g.origin + glm::ivec3(g.resolution - 1);
            forEachVoxelSurface(*voxels, int(c), box, [&](const VoxelSurfaceArea& s) {
                t->addSurface({s.voxel - g.origin, s.coverage, s.vectorCoverage, s.albedo});
            });
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
    const auto t0 = std::chrono::steady_clock::now();
    stats_ = {};
    // Fitted: every bounce now; a number of sweeps continues from the last update's reflections.
    const bool incremental = desc_.bounces && desc_.sweeps != kFittedInteger;
    const int maxBounces = !desc_.bounces ? 1 : incremental ? desc_.sweeps : 256;
    const int n = desc_.resolution;
    for (std::size_t c = 0; c < transports_.size(); ++c) {
        for (int set = 0; set < 2; ++set) {
            const OrdinatesTransport::Sources& sources = set == 0 ? ring_[c] : inner_[c];
            auto& cube = cubes_[2 * c + std::size_t(set)];
            const GLuint id = textures_[2 * c + std::size_t(set)].id();
            if (gl_) {
                // The sweeps write the texture; the CPU keeps no copy (irradiance() reads it back).
                const int sweeps = gl_->solve(*transports_[c], sources, desc_.occlusion, maxBounces, id);
                stats_.sweeps = std::max(stats_.sweeps, sweeps);
                continue;
            }
            if (set == 1 && sources.watts <= 0.0) {
                for (auto& f : cube) f.assign(transports_[c]->grid().cellCount(), glm::vec4(0.0f));
            } else {
                std::vector<glm::vec3>* carry = incremental ? &carry_[2 * c + std::size_t(set)] : nullptr;
                cube = transports_[c]->solve(sources, desc_.occlusion, maxBounces, carry);
                const OrdinatesStats& st = transports_[c]->stats();
                stats_.sweeps = std::max(stats_.sweeps, st.sweeps);
                if (incremental) {
                    stats_.leftWatts += st.leftWatts;
                    if (st.leftWatts >= kOrdinatesConverged * st.emittedWatts) stats_.converged = false;
                }
            }
            for (int f = 0; f < kOrdinateFaces; ++f)
                glTextureSubImage3D(id, 0, 0, 0, f * n, n, n, n, GL_RGBA, GL_FLOAT, cube[std::size_t(f)].data());
        }
        stats_.emittedWatts += ring_[c].watts;
        stats_.surfaceCells += transports_[c]->surfaceCells();
    }
    if (!ring_.empty()) stats_.outsideWatts = ring_.back().outsideWatts;
    stats_.solveMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

std::array<std::vector<glm::vec4>, kOrdinateFaces> OrdinatesLight::irradiance(std::size_t c) const {
    std::array<std::vector<glm::vec4>, kOrdinateFaces> sum = cubes_.at(2 * c), inner = cubes_.at(2 * c + 1);
    if (gl_) {
        sum = readCube(textures_.at(2 * c).id(), desc_.resolution);
        inner = readCube(textures_.at(2 * c + 1).id(), desc_.resolution);
    }
    for (int f = 0; f < kOrdinateFaces; ++f)
        for (std::size_t i = 0; i < sum[std::size_t(f)].size() && i < inner[std::size_t(f)].size(); ++i)
            sum[std::size_t(f)][i] += inner[std::size_t(f)][i];
    return sum;
}

void OrdinatesLight::apply(const GBufferView& g) const {
    program_.use();
    bindGBufferTextures(program_, g);
    program_.set("uCascadeCount", int(placements_.size()));
    program_.set("uApplyNormalOffset", desc_.applyNormalOffset);
    program_.set("uResolution", desc_.resolution);
    program_.set("uEye", g.eye);
    program_.set("uGlossy", desc_.glossy ? 1 : 0);
    setCascadeUniforms(program_, placements_);
    for (std::size_t c = 0; c < std::size_t(kLpvMaxCascades); ++c) {
        const std::string idx = "[" + std::to_string(c) + "]";
        const bool used = c < placements_.size();
        if (used) program_.set(("uCellSize" + idx).c_str(), placements_[c].grid.cellSize);
        // Units 4..: ring and inner cube of each cascade (unused samplers point at unit 4).
        for (int set = 0; set < 2; ++set) {
            const GLuint unit = GLuint(4 + 2 * c + std::size_t(set));
            if (used) glBindTextureUnit(unit, textures_[2 * c + std::size_t(set)].id());
            program_.set(((set == 0 ? "uRing" : "uInner") + idx).c_str(), int(used ? unit : 4));
        }
    }
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

}  // namespace voxgi
