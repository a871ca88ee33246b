#include "gi/lpv/lpv_technique.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cmath>

#include <tbb/parallel_for.h>

#include "gi/lpv/cascades.h"
#include "gi/lpv/gl_cascade_uniforms.h"
#include "gi/lpv/gl_injection.h"
#include "gi/lpv/lpv_debug_views.h"
#include "gi/lpv/gl_propagation.h"
#include "gi/lpv/injection.h"
#include "gi/lpv/lpv_dump.h"
#include "gi/lpv/ordinates_light.h"
#include "gi/lpv/propagation.h"
#include "gi/lpv/rsm.h"
#include "gi/lpv/sky_bounce.h"
#include "gi/lpv/static_blockers.h"
#include "gi/sky/sky_volume.h"
#include "gi/sky/sky_volume_texture.h"
#include "gl/program.h"
#include "gl/resources.h"
#include "gl/scene_gpu.h"
#include "scenes/errors.h"
#include "shaders/lpv/limits.h"
#include "shaders/shared/gbuffer.h"

namespace voxgi {

namespace {

double millisecondsSince(std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

SurfelSource gbufferSurfels(const GBufferView& g, int target) {
    SurfelSource source;
    const GBufferSampling sampling = GBufferSampling::of(g, target);
    if (sampling.count() <= 0) return source;
    std::vector<float> pos = gl::readTexture(g.position, g.width, g.height, 4);
    std::vector<float> nrm = gl::readTexture(g.normal, g.width, g.height, 4);
    std::vector<float> alb = gl::readTexture(g.albedo, g.width, g.height, 4);
    std::vector<float> emi = gl::readTexture(g.emission, g.width, g.height, 4);
    const int stride = sampling.stride;
    const float pixel = sampling.pixel;
    const glm::vec3 forward = sampling.forward;
    for (int y = stride / 2; y < g.height; y += stride)
        for (int x = stride / 2; x < g.width; x += stride) {
            std::size_t i = (std::size_t(y) * std::size_t(g.width) + std::size_t(x)) * 4;
            if (!shading::gbufferHit(glm::vec4(pos[i], pos[i + 1], pos[i + 2], pos[i + 3]))) continue;
            Surfel s;
            s.position = {pos[i], pos[i + 1], pos[i + 2]};
            s.normal = glm::normalize(glm::vec3(nrm[i], nrm[i + 1], nrm[i + 2]));
            s.albedo = shading::gbufferDiffuseAlbedo(glm::vec4(pos[i], pos[i + 1], pos[i + 2], pos[i + 3]),
                                                     glm::vec4(alb[i], alb[i + 1], alb[i + 2], alb[i + 3]),
                                                     glm::vec4(emi[i], emi[i + 1], emi[i + 2], emi[i + 3]));
            glm::vec3 d = s.position - g.eye;
            float dist = glm::length(d);
            glm::vec3 w = d / dist;
            float c = std::max(glm::dot(w, forward), 1e-3f);
            float solidAngle = pixel * pixel * c * c * c * float(stride * stride);
            s.area = solidAngle * dist * dist / std::max(std::abs(glm::dot(s.normal, w)), 0.05f);
            source.surfels.push_back(s);
        }
    return source;
}

namespace {

class LpvTechnique final : public GiTechnique {
    const Scene& scene;
    LpvDesc desc;
    bool cascaded;
    RsmRenderer rsm;
    gl::Program apply;
    std::vector<CascadePlacement> placements;
    // Per cascade, the ring light (VPLs of its own border region and beyond) and the inner light
    // (VPLs finer cascades hold), see gi/lpv/cascades.h; cascade 0's inner light stays empty.
    std::vector<LightVolume> injected, accumulated, injectedInner, accumulatedInner;
    std::vector<BlockerVolume> geometry;
    std::vector<CpuPropagator> propagators;
    std::vector<std::unique_ptr<GlPropagator>> glPropagators;
    std::unique_ptr<GlInjector> glInjector;                 // gl back end: injection on the GPU
    std::vector<BlockerVolume> statics;                      // static blockers per cascade, kept
    std::vector<std::unique_ptr<GlBlockerVolume>> glStatic;  // the same on the GPU (gl back end)
    std::vector<bool> staticsMerged;  // gl: the cascade's geometry volume holds its static blockers alone
    std::vector<gl::Handle> textures;  // 6 per cascade: ring r, g, b, inner r, g, b
    std::vector<glm::ivec3> lastOrigins;
    std::unique_ptr<SparseGeometryVolume> voxels;  // static geometry, voxelized once (cached .vdb)
    std::unique_ptr<OrdinatesLight> ordinatesLight;  // lpv.transport=ordinates: replaces the SH volumes
    std::unique_ptr<SkyBounceFace> skyBounce;      // made on the first update that runs lpv.sky_bounce
    glm::vec3 skyBounceEye{0.0f}, skyBounceForward{0.0f};  // the view the sky bounce was injected from
    // The lights and the sky (its volume's Sky::revision, -1 without one) the light was made with.
    std::vector<Light> lastLights;
    int lastSkyRevision = -1;
    bool valid = false;
    bool complete = true;  // no bounces left to carry into the next update (lpv.sweeps=N)

public:
    LpvTechnique(const Scene& s, const LpvDesc& d, bool c)
        : scene(s), desc(d), cascaded(c), rsm(d.rsmSize),
          apply(gl::Program::graphics("frame/fullscreen.vert", "lpv/apply.frag")) {
        // The cell size is fixed once, from the scene camera, so moving cameras keep cascades
        // (and the voxelized blockers) consistent.
        desc.cellSize = finestCellSize(desc, scene.bounds(), scene.camera.eye);
        if (desc.staticBlockers && scene.triangleCount() > 0) {
            VoxelizeSettings vs;
            vs.voxelSize = desc.cellSize;
            vs.levels = desc.cascades;
            // The LPV reads voxel indices, areas over the voxel's face area, normals and albedo:
            // all the same for the scene and its voxel scaled by one power of two (exactly, in
            // floating point). Cells below OpenVDB's smallest voxel (a box of 0.1 mm) voxelize a
            // copy scaled up; without it the ordinates would have no surfaces to stop the light.
            float scale = 1.0f;
            while (vs.voxelSize * scale < kSmallestVoxelSize && scale < 1e30f) scale *= 2.0f;
            Scene scaled;
            if (scale > 1.0f) {
                scaled = scene;
                for (Mesh& m : scaled.meshes)
                    for (glm::vec3& p : m.positions) p *= scale;
                vs.voxelSize *= scale;
            }
            try {
                voxels = std::make_unique<SparseGeometryVolume>(
                    loadOrBuildGeometryVolume(scale > 1.0f ? scaled : scene, vs, geometryCacheDir()));
            } catch (const InputError& e) {
                // OpenVDB cannot hold cells this small (or this many): dynamic blockers only.
                std::fprintf(stderr, "voxgi: lpv: static blockers off (%s)\n", e.what());
            }
        }
        if (desc.transport == LpvTransport::Ordinates) {
            ordinatesLight = std::make_unique<OrdinatesLight>(desc, scene);
            return;
        }
        for (auto* v : {&injected, &accumulated, &injectedInner, &accumulatedInner}) v->resize(std::size_t(desc.cascades));
        geometry.resize(std::size_t(desc.cascades));
        propagators.resize(std::size_t(desc.cascades));
        if (desc.backend == Backend::Gl) {
            for (int c = 0; c < desc.cascades; ++c)
                glPropagators.push_back(std::make_unique<GlPropagator>(desc.resolution, c == 0 ? 1 : 2));
            glInjector = std::make_unique<GlInjector>(desc.resolution);
        }
        for (int i = 0; i < 6 * desc.cascades; ++i)
            textures.push_back(gl::createTexture(GL_TEXTURE_3D, GL_RGBA32F, desc.resolution, desc.resolution,
                                                 desc.resolution));
    }

    void place(const GBufferView& g) {
        glm::vec3 view = scene.camera.target - scene.camera.eye;
        placements = placeCascades(desc, scene.bounds(), g.eye, view);
    }

    bool placementChanged() const {
        if (lastOrigins.size() != placements.size()) return true;
        for (std::size_t i = 0; i < placements.size(); ++i)
            if (placements[i].grid.origin != lastOrigins[i]) return true;
        return false;
    }

    std::string name() const override { return cascaded ? "clpv" : "lpv"; }

    void update(const FrameInput& input, const GBufferView& g) override {
        // Without lights there is nothing to inject: the plan runs no pass at all.
        if (!input.plan.runs("lpv.propagate")) return;
        place(g);
        // The sky bounce comes from the surfaces on screen: a new view is new light (the
        // sub-pixel jitter of accumulating frames is not).
        const bool bounceSky = input.plan.runs("lpv.sky_bounce") && input.sky;
        const glm::vec3 forward = viewForward(g.viewProjection);
        // (The ordinates bounce the sky off every voxelized surface, whatever the view.)
        const bool viewChanged = bounceSky && !ordinatesLight && (g.eye != skyBounceEye || forward != skyBounceForward);
        // Static scene, lights and placement: the propagated light is still valid. The viewer
        // moves lights between frames, and a sky that changed arrives as a new volume.
        const int skyRevision = input.sky ? input.sky->volume().skyRevision() : -1;
        const bool lightChanged = input.scene.lights != lastLights || skyRevision != lastSkyRevision;
        if (desc.reuse && valid && complete && !placementChanged() && !viewChanged && !lightChanged) return;
        lastLights = input.scene.lights;
        lastSkyRevision = skyRevision;
        skyBounceEye = g.eye;
        skyBounceForward = forward;
        lastOrigins.clear();
        for (const auto& p : placements) lastOrigins.push_back(p.grid.origin);
        if (ordinatesLight) {
            updateOrdinates(input, bounceSky);
            return;
        }
        if (glInjector) {
            updateOnGpu(input, g);
            return;
        }

        // Sources merge in order: RSM faces, the camera, static blockers.
        double injectMs = 0.0, blockersMs = 0.0;
        const InjectionOffsets offsets{desc.injectNormalOffset, desc.injectLightOffset};
        std::vector<BlockerVolume> scratch(placements.size());
        for (std::size_t c = 0; c < placements.size(); ++c) {
            injected[c].reset(placements[c].grid);
            injectedInner[c].reset(placements[c].grid);
            geometry[c].reset(placements[c].grid);
            scratch[c].reset(placements[c].grid);
        }
        forEachRsmFace(input, [&](const SurfelSource& surfels) {
            auto t0 = std::chrono::steady_clock::now();
            // Cascades write their own volumes: one task each.
            tbb::parallel_for(std::size_t(0), placements.size(), [&](std::size_t c) {
                injectLight(surfels, offsets, placements, c, injected[c], injectedInner[c]);
            });
            injectMs += millisecondsSince(t0);
            if (!desc.surfelBlockers) return;
            t0 = std::chrono::steady_clock::now();
            for (std::size_t c = 0; c < placements.size(); ++c) injectBlockers(surfels, scratch[c], geometry[c]);
            blockersMs += millisecondsSince(t0);
        });
        if (bounceSky) {
            const auto t0 = std::chrono::steady_clock::now();
            const SurfelSource surfels = readSurfels(skyBounceFace().render(g, *input.sky));
            tbb::parallel_for(std::size_t(0), placements.size(), [&](std::size_t c) {
                injectLight(surfels, offsets, placements, c, injected[c], injectedInner[c]);
            });
            input.timers.addCpu("lpv.sky_bounce", millisecondsSince(t0));
        }

        SurfelSource camera;
        if (desc.surfelBlockers && input.plan.runs("lpv.gbuffer_readback")) {
            const auto t0 = std::chrono::steady_clock::now();
            camera = gbufferSurfels(g, desc.gbufferBlockerSize);
            input.timers.addCpu("lpv.gbuffer_readback", millisecondsSince(t0));
        }
        input.timers.addCpu("lpv.inject", injectMs);

        if (input.plan.runs("lpv.static_blockers")) refreshStatics(input);
        auto t0 = std::chrono::steady_clock::now();
        for (std::size_t c = 0; c < placements.size(); ++c) {
            if (!desc.surfelBlockers) {
                // The static blockers alone: the same volume while the placement stays, so the
                // propagator keeps its operator.
                if (c < statics.size()) geometry[c] = statics[c];
                continue;
            }
            injectBlockers(camera, scratch[c], geometry[c]);
            if (c < statics.size()) geometry[c].mergeMax(statics[c]);
        }
        input.timers.addCpu("lpv.blockers", blockersMs + millisecondsSince(t0));

        PropagationOptions options{desc.occlusion, desc.bounces};
        t0 = std::chrono::steady_clock::now();
        last = {};
        for (std::size_t c = 0; c < placements.size(); ++c) {
            // The inner light goes through the same geometry: the operator is built once.
            for (int set = 0; set < (c == 0 ? 1 : 2); ++set) {
                propagators[c].propagate(set == 0 ? injected[c] : injectedInner[c], geometry[c], propagationSteps(desc),
                                         options, set == 0 ? accumulated[c] : accumulatedInner[c], desc.sparse);
                const PropagationStats& st = propagators[c].stats();
                last.operatorMs += st.operatorMs;
                last.operatorBuilds += st.operatorBuilt ? 1 : 0;
                last.stepsMs += st.stepsMs;
                last.activeBricks += st.activeBricks;
                last.totalBricks += st.totalBricks;
                last.stepsRun = std::max(last.stepsRun, st.stepsRun);
            }
        }
        input.timers.addCpu("lpv.propagate", millisecondsSince(t0));

        t0 = std::chrono::steady_clock::now();
        const int n = desc.resolution;
        for (std::size_t c = 0; c < placements.size(); ++c) {
            const LightVolume& inner = accumulatedInner[c];
            const std::vector<glm::vec4>* channels[6] = {&accumulated[c].r, &accumulated[c].g, &accumulated[c].b,
                                                         &inner.r, &inner.g, &inner.b};
            for (int k = 0; k < (c == 0 ? 3 : 6); ++k)
                glTextureSubImage3D(textures[6 * c + std::size_t(k)].id(), 0, 0, 0, 0, n, n, n, GL_RGBA, GL_FLOAT,
                                    channels[k]->data());
        }
        input.timers.addCpu("lpv.upload", millisecondsSince(t0));
        valid = true;
    }

    // Renders the RSM faces in batches (RsmRenderer::facesPerBatch) and hands each face's surfels
    // to `use`, dropped before the next face is read back (a 4096^2 face holds 1 GiB of them);
    // the rendering and read-back go to the lpv.rsm timer.
    template <typename Use>
    void forEachRsmFace(const FrameInput& input, Use use) {
        double rsmMs = 0.0;
        const std::size_t faceCount = rsmFaceCount(scene), batch = rsm.facesPerBatch();
        for (std::size_t first = 0; first < faceCount; first += batch) {
            auto t0 = std::chrono::steady_clock::now();
            const std::vector<RsmFace>& faces = rsm.renderToTextures(scene, input.sceneGpu, first, batch);
            rsmMs += millisecondsSince(t0);
            for (const RsmFace& face : faces) {
                t0 = std::chrono::steady_clock::now();
                const SurfelSource surfels = readSurfels(face);
                rsmMs += millisecondsSince(t0);
                use(surfels);
            }
        }
        if (faceCount > 0) input.timers.addCpu("lpv.rsm", rsmMs);
    }

    // lpv.transport=ordinates: the surfaces once per placement, the surfels' light each update.
    void updateOrdinates(const FrameInput& input, bool bounceSky) {
        auto t0 = std::chrono::steady_clock::now();
        if (ordinatesLight->place(placements, voxels.get())) input.timers.addCpu("lpv.static_blockers", millisecondsSince(t0));
        ordinatesLight->clearSources();
        double injectMs = 0.0;
        forEachRsmFace(input, [&](const SurfelSource& surfels) {
            const auto start = std::chrono::steady_clock::now();
            ordinatesLight->addSurfels(surfels);
            injectMs += millisecondsSince(start);
        });
        if (bounceSky) {
            t0 = std::chrono::steady_clock::now();
            ordinatesLight->addSkyBounce(input.sky->volume());
            input.timers.addCpu("lpv.sky_bounce", millisecondsSince(t0));
        }
        input.timers.addCpu("lpv.inject", injectMs);
        if (desc.backend == Backend::Gl) {
            // The sweeps' dispatches: GPU time as well as the CPU's (which waits for each sweep's
            // power read-back).
            input.timers.begin("lpv.propagate");
            ordinatesLight->solve();
            input.timers.end();
        } else {
            t0 = std::chrono::steady_clock::now();
            ordinatesLight->solve();
            input.timers.addCpu("lpv.propagate", millisecondsSince(t0));
        }
        // With lpv.sweeps=N the light is complete only once the carried bounces have died out:
        // until then every frame updates, even in a still scene.
        complete = ordinatesLight->stats().converged;
        valid = true;
    }

    GlCascadeTargets glTargets(std::size_t c, int set = 0) const {
        GlCascadeTargets t;
        t.grid = placements[c].grid;
        for (int k = 0; k < 3; ++k) t.light[k] = glPropagators[c]->injected(k, set);
        t.blocker = glPropagators[c]->blocker();
        t.albedo = glPropagators[c]->albedo();
        return t;
    }

    SkyBounceFace& skyBounceFace() {
        if (!skyBounce) skyBounce = std::make_unique<SkyBounceFace>(desc.skyBounceSize);
        return *skyBounce;
    }

    // The voxelized static blockers of each cascade: made once per placement (for `lpv` once;
    // for `clpv` when a cascade's snapped origin moves) and kept, so an update only redoes the
    // dynamic blockers (RSM and G-buffer). Returns which cascades changed.
    std::vector<bool> refreshStatics(const FrameInput& input) {
        std::vector<bool> changed(placements.size(), false);
        if (!voxels) return changed;
        const auto t0 = std::chrono::steady_clock::now();
        statics.resize(placements.size());
        bool any = false;
        for (std::size_t c = 0; c < placements.size(); ++c) {
            const CascadeGrid& grid = placements[c].grid;
            if (!statics[c].blocker.empty() && statics[c].grid.origin == grid.origin &&
                statics[c].grid.cellSize == grid.cellSize && statics[c].grid.resolution == grid.resolution)
                continue;
            statics[c].reset(grid);
            staticBlockers(*voxels, int(c), statics[c]);
            changed[c] = any = true;
        }
        if (any) input.timers.addCpu("lpv.static_blockers", millisecondsSince(t0));
        return changed;
    }

    // The gl back end: RSM, injection and propagation without leaving the GPU. RSM faces are
    // rendered in batches that bound their texture memory (one batch unless the maps are large
    // or the lights many; each batch adds one sample to the rsm, inject and blockers timers).
    void updateOnGpu(const FrameInput& input, const GBufferView& g) {
        staticsMerged.resize(placements.size(), false);
        if (input.plan.runs("lpv.static_blockers")) {
            const std::vector<bool> changed = refreshStatics(input);
            glStatic.resize(statics.size());
            for (std::size_t c = 0; c < statics.size(); ++c) {
                if (changed[c]) staticsMerged[c] = false;
                if (!changed[c] && glStatic[c]) continue;
                if (!glStatic[c]) glStatic[c] = std::make_unique<GlBlockerVolume>(desc.resolution);
                glStatic[c]->upload(statics[c]);
            }
        }
        const InjectionOffsets offsets{desc.injectNormalOffset, desc.injectLightOffset};
        const std::size_t faceCount = rsmFaceCount(scene), batch = rsm.facesPerBatch();
        const bool bounceSky = input.plan.runs("lpv.sky_bounce") && input.sky;
        static const std::vector<RsmFace> noFaces;
        for (std::size_t first = 0; first == 0 || first < faceCount; first += batch) {
            const bool firstBatch = first == 0, lastBatch = first + batch >= faceCount;
            const std::vector<RsmFace>* faces = &noFaces;
            if (faceCount > 0) {
                input.timers.begin("lpv.rsm");
                faces = &rsm.renderToTextures(scene, input.sceneGpu, first, batch);
                input.timers.end();
            }
            const RsmFace* skyFace = nullptr;
            if (bounceSky && lastBatch) {
                input.timers.begin("lpv.sky_bounce");
                skyFace = &skyBounceFace().render(g, *input.sky);
                input.timers.end();
            }

            input.timers.begin("lpv.inject");
            for (std::size_t c = 0; c < placements.size(); ++c)
                for (int set = 0; set < glPropagators[c]->lightSets(); ++set) {
                    GlCascadeTargets t = glTargets(c, set);
                    if (firstBatch) glInjector->clearLight(t);
                    for (const RsmFace& face : *faces) glInjector->injectLight(face, offsets, t, placements, c, set == 1);
                    if (skyFace) glInjector->injectLight(*skyFace, offsets, t, placements, c, set == 1);
                }
            input.timers.end();

            // Sources merge in the CPU back end's order: RSM faces, the camera, static blockers.
            input.timers.begin("lpv.blockers");
            GBufferSampling sampling = GBufferSampling::of(g, desc.gbufferBlockerSize);
            for (std::size_t c = 0; c < placements.size(); ++c) {
                GlCascadeTargets t = glTargets(c);
                const bool surfels = desc.surfelBlockers;
                // Static blockers alone stay in the geometry volume until the cascade moves.
                if (!surfels && (!lastBatch || staticsMerged[c])) continue;
                if (firstBatch || !surfels) glInjector->clearGeometry(t);
                if (surfels)
                    for (const RsmFace& face : *faces) glInjector->injectBlockers(face, t);
                if (!lastBatch) continue;
                if (surfels) glInjector->injectBlockers(g, sampling, t);
                if (voxels && c < glStatic.size()) glInjector->mergeBlockers(*glStatic[c], t);
                staticsMerged[c] = !surfels;
            }
            input.timers.end();
        }

        input.timers.begin("lpv.propagate");
        PropagationOptions options{desc.occlusion, desc.bounces};
        for (std::size_t c = 0; c < placements.size(); ++c) {
            glPropagators[c]->propagateInjected(propagationSteps(desc), options);
            accumulated[c].grid = placements[c].grid;
            accumulatedInner[c].grid = placements[c].grid;
            geometry[c].grid = placements[c].grid;
        }
        input.timers.end();
        valid = true;
    }

    void applyIndirect(const FrameInput& input, const GBufferView& g) override {
        if (!input.plan.runs("lpv.apply") || placements.empty()) return;
        input.timers.begin("lpv.apply");
        if (ordinatesLight) {
            ordinatesLight->apply(g);
            input.timers.end();
            return;
        }
        apply.use();
        bindGBufferTextures(apply, g);
        apply.set("uCascadeCount", int(placements.size()));
        apply.set("uEye", g.eye);
        apply.set("uApplyNormalOffset", desc.applyNormalOffset);
        apply.set("uDampening", desc.dampening);
        apply.set("uGlossy", desc.glossy ? 1 : 0);
        setCascadeUniforms(apply, placements);
        // Every sampler of the arrays needs a 3D texture unit, including unused cascades.
        const char* ringNames[3] = {"uLpvR", "uLpvG", "uLpvB"};
        const char* innerNames[3] = {"uInnerR", "uInnerG", "uInnerB"};
        for (std::size_t c = 0; c < std::size_t(kLpvMaxCascades); ++c) {
            const std::string idx = "[" + std::to_string(c) + "]", innerIdx = "[" + std::to_string(int(c) - 1) + "]";
            const bool used = c < placements.size();
            if (used) apply.set(("uCellSize" + idx).c_str(), placements[c].grid.cellSize);
            for (int k = 0; k < 3; ++k) {
                // Units: 4.. ring of every cascade, then the inner volumes of cascades 1...
                const GLuint ringUnit = GLuint(4 + 3 * c + std::size_t(k));
                if (used) glBindTextureUnit(ringUnit, glPropagators.empty() ? textures[6 * c + std::size_t(k)].id()
                                                                            : glPropagators[c]->accumulated(k, 0));
                apply.set((std::string(ringNames[k]) + idx).c_str(), int(used ? ringUnit : 4));
                if (c == 0) continue;
                const GLuint innerUnit = GLuint(4 + 3 * kLpvMaxCascades + 3 * (c - 1) + std::size_t(k));
                if (used) glBindTextureUnit(innerUnit, glPropagators.empty() ? textures[6 * c + 3 + std::size_t(k)].id()
                                                                             : glPropagators[c]->accumulated(k, 1));
                apply.set((std::string(innerNames[k]) + innerIdx).c_str(), int(used ? innerUnit : 4));
            }
        }
        glDrawArrays(GL_TRIANGLES, 0, 3);
        input.timers.end();
    }

    void dumpVdb(const std::string& path) const override {
        if (!valid) throw NotImplementedError("lpv: nothing to dump before the first frame");
        if (ordinatesLight) {
            std::vector<OrdinatesDump> cascades;
            for (std::size_t c = 0; c < placements.size(); ++c)
                cascades.push_back({&ordinatesLight->transport(c), ordinatesLight->irradiance(c)});
            writeOrdinatesVdb(path, cascades);
            return;
        }
        writeLpvVdb(path, lightVolumes(), geometryVolumes());
    }

    DebugDrawing debugView(const std::string& view, const DebugViewContext& context) const override {
        if (view == kCascadeBoundsView) {
            const Camera& c = context.camera;
            return cascadeBounds(placeCascades(desc, scene.bounds(), c.eye, c.target - c.eye));
        }
        if (view == kLpvBricksView && valid && ordinatesLight) {
            const int c = lpvBricksOptions().read(context.options).cascade;
            if (c >= int(placements.size())) return {};
            return lpvBricks(ordinatesLight->transport(std::size_t(c)), c, int(placements.size()));
        }
        if (view == kLpvCellsView && valid) {
            const LpvCellsOptions o = lpvCellsOptions().read(context.options);
            if (o.cascade >= int(placements.size())) return {};
            if (ordinatesLight)
                return lpvCellSpheres(ordinatesLight->transport(std::size_t(o.cascade)),
                                      ordinatesLight->irradiance(std::size_t(o.cascade)), o.stride, context.exposureStops);
            return lpvCellSpheres(lightVolume(std::size_t(o.cascade)), o.stride, context.exposureStops);
        }
        return {};
    }

    // The CPU propagation's parts (the gl back end propagates in one dispatch per step).
    std::vector<TechniqueStat> stats() const override {
        if (ordinatesLight) {
            const OrdinatesLight::Stats& o = ordinatesLight->stats();
            return {{"ordinates_solve", o.solveMs, "ms"},
                    {"ordinate_sweeps", double(o.sweeps), "sweeps"},
                    {"surface_cells", double(o.surfaceCells), "cells"},
                    {"emitted", o.emittedWatts, "W"},
                    {"emitted_outside", o.outsideWatts, "W"},
                    {"light_bricks", double(o.bricks), "bricks"},
                    {"grid_bricks", double(o.gridBricks), "bricks"},
                    {"light_pool", double(o.poolBytes) / (1024.0 * 1024.0), "MiB"},
                    {"reflections_left", o.leftWatts, "W"},
                    {"tap_masks", o.tapMasksMs, "ms"}};
        }
        if (desc.backend != Backend::Cpu) return {};
        return {{"propagate_operator", last.operatorMs, "ms"},
                {"operator_builds", double(last.operatorBuilds), "operators"},
                {"propagate_steps", last.stepsMs, "ms"},
                {"steps_run", double(last.stepsRun), "steps"},
                {"active_bricks", double(last.activeBricks), "bricks"},
                {"total_bricks", double(last.totalBricks), "bricks"}};
    }

private:
    // What the CPU propagators did in the last update, summed over cascades.
    struct {
        double operatorMs = 0.0, stepsMs = 0.0;
        std::size_t activeBricks = 0, totalBricks = 0;
        int operatorBuilds = 0;  // propagations whose operator was built, not kept from the last update
        int stepsRun = 0;  // the most any cascade took (propagation stops when no light is left)
    } last;

    // The propagated light of a cascade and the geometry of every cascade, read back from the
    // GPU with the gl back end.
    // The cascade's light from every surface inside it: ring + inner.
    LightVolume lightVolume(std::size_t c) const {
        LightVolume light = accumulated[c], inner = accumulatedInner[c];
        if (c < glPropagators.size()) {
            glPropagators[c]->readBack(light, 0);
            if (glPropagators[c]->lightSets() > 1) glPropagators[c]->readBack(inner, 1);
            else inner = {};
        }
        if (inner.r.size() != light.r.size()) return light;
        for (std::size_t i = 0; i < light.r.size(); ++i) {
            light.r[i] += inner.r[i];
            light.g[i] += inner.g[i];
            light.b[i] += inner.b[i];
        }
        return light;
    }
    std::vector<LightVolume> lightVolumes() const {
        std::vector<LightVolume> light;
        for (std::size_t c = 0; c < accumulated.size(); ++c) light.push_back(lightVolume(c));
        return light;
    }
    std::vector<BlockerVolume> geometryVolumes() const {
        std::vector<BlockerVolume> out = geometry;
        for (std::size_t c = 0; c < glPropagators.size(); ++c) glPropagators[c]->readBackGeometry(out[c]);
        return out;
    }
};

}  // namespace

std::unique_ptr<GiTechnique> createLpvTechnique(const Scene& scene, const LpvDesc& desc, bool cascaded) {
    return std::make_unique<LpvTechnique>(scene, desc, cascaded);
}

}  // namespace voxgi
