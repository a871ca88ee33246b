#include "gi/hybrid/hybrid_technique.h"

#include <chrono>
#include <memory>

#include <tbb/task_group.h>

#include "gi/gbuffer_upload.h"
#include "gi/hybrid/mirror_paths.h"
#include "gi/raytrace/ray_tracer.h"
#include "gl/program.h"
#include "gl/resources.h"

namespace voxgi {

namespace {

// One layer on the GPU: the G-buffer the frame lights (its target takes the layer's light),
// each pixel's viewer and weight.
struct LayerTextures {
    UploadedGBuffer surfaces;
    gl::Handle viewOrigin, weight;
    // Where the textures may hold something other than zero: the last upload's bounds. A frame
    // uploads its own bounds and these, and nothing outside both changed.
    glm::ivec4 held{0};
};

class HybridTechnique final : public GiTechnique {
public:
    HybridTechnique(const Scene& scene, const HybridDesc& desc, std::unique_ptr<GiTechnique> diffuse)
        : desc_(desc), diffuse_(std::move(diffuse)), tracer_(scene),
          composite_(gl::Program::graphics("frame/fullscreen.vert", "hybrid/composite.frag")),
          resolve_(gl::Program::graphics("frame/fullscreen.vert", "hybrid/resolve.frag")) {}

    std::string name() const override { return "hybrid"; }
    float tracedRoughness() const override { return desc_.glossyRoughness; }

    ~HybridTechnique() override {
        // A trace still running reads this technique's tracer and the job's buffers.
        if (pending_) pending_->tasks.wait();
    }

    void update(const FrameInput& input, const GBufferView& g) override {
        if (diffuse_) diffuse_->update(input, g);
        active_ = 0;
        if (!input.plan.runs("hybrid.trace")) return;
        const auto t0 = std::chrono::steady_clock::now();
        if (pending_ && (pending_->in.width != g.width || pending_->in.height != g.height)) {
            // Traced for another image size: of no use to this frame.
            pending_->tasks.wait();
            pending_.reset();
        }
        if (!desc_.overlap || !pending_) {
            // Every frame's own rays (and the first frame's when traced ahead).
            std::unique_ptr<TraceJob> job = readBack(g, std::uint32_t(input.frameIndex));
            const bool replay = desc_.replayBare && !desc_.overlap;  // serial frames only
            if (replay) tracer_.startLog();
            const auto t1 = std::chrono::steady_clock::now();
            job->trace(tracer_);
            input.timers.addCpu("hybrid.trace", millisecondsSince(t0));
            if (replay) replayBare(job->paths, 1e-3 * millisecondsSince(t1));
            uploadPaths(input, job->paths, g);
        } else {
            // The rays traced while the GPU lit the last frame; the wait is what tracing still
            // costs this frame (0 when the GPU took longer).
            pending_->tasks.wait();
            input.timers.addCpu("hybrid.trace", millisecondsSince(t0));
            input.timers.addCpu("hybrid.trace_overlapped", pending_->traceMs);
            uploadPaths(input, pending_->paths, g);
            pending_.reset();
        }
        if (!desc_.overlap) return;
        // The next frame's rays, from this G-buffer, while the GPU lights this frame.
        pending_ = readBack(g, std::uint32_t(input.frameIndex + 1));
        TraceJob* job = pending_.get();
        job->tasks.run([this, job] {
            const auto start = std::chrono::steady_clock::now();
            job->trace(tracer_);
            job->traceMs = millisecondsSince(start);
        });
    }

    void applyIndirect(const FrameInput& input, const GBufferView& g) override {
        if (diffuse_) diffuse_->applyIndirect(input, g);
    }

    std::vector<SecondaryLayerView> secondaryLayers() const override {
        std::vector<SecondaryLayerView> out;
        for (std::size_t l = 0; l < active_; ++l) {
            const LayerTextures& t = layers_[l];
            SecondaryLayerView v;
            v.surfaces = t.surfaces.view;
            v.surfaces.eye = eye_;
            v.surfaces.viewProjection = viewProjection_;
            v.surfaces.viewOrigin = t.viewOrigin.id();
            // Rays go on from these surfaces only through mirror-like lobes.
            v.surfaces.tracedRoughness = 0.0f;
            v.lightFramebuffer = t.surfaces.framebuffer.id();
            v.scissor = bounds_[l];
            out.push_back(v);
        }
        return out;
    }

    // The rays' light is gathered per pixel into two targets (direct: emitters and sky after one
    // scattering; indirect: the rest), then resolved into the frame, glossy pixels through the
    // edge-aware filter (hybrid/resolve.frag). The caller has set additive blending.
    void composite(const FrameInput& input, GLuint directFramebuffer, GLuint indirectFramebuffer) override {
        if (!input.plan.runs("hybrid.composite") || width_ == 0) return;
        input.timers.begin("hybrid.composite");
        const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
        for (const gl::Handle& f : reflectionFramebuffer_) glClearNamedFramebufferfv(f.id(), GL_COLOR, 0, zero);
        composite_.use();
        composite_.set("uRadiance", 0);
        composite_.set("uWeight", 1);
        auto draw = [&](GLuint framebuffer, GLuint radiance, GLuint weight) {
            glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
            glBindTextureUnit(0, radiance);
            glBindTextureUnit(1, weight ? weight : radiance);
            composite_.set("uWeighted", weight ? 1 : 0);
            glDrawArrays(GL_TRIANGLES, 0, 3);
        };
        const GLuint direct = reflectionFramebuffer_[0].id(), indirect = reflectionFramebuffer_[1].id();
        glEnable(GL_SCISSOR_TEST);
        for (std::size_t l = 0; l < active_; ++l) {
            glScissor(bounds_[l].x, bounds_[l].y, bounds_[l].z, bounds_[l].w);
            draw(indirect, layers_[l].surfaces.target.id(), layers_[l].weight.id());
        }
        glDisable(GL_SCISSOR_TEST);
        draw(indirect, emittedIndirect_.id(), 0);
        draw(direct, emittedDirect_.id(), 0);

        resolve_.use();
        bindGBufferTextures(resolve_, primary_);
        resolve_.set("uReflection", 4);
        resolve_.set("uEye", eye_);
        resolve_.set("uGlossyRoughness", desc_.glossyRoughness);
        resolve_.set("uRadius", desc_.denoiseRadius);
        for (int k = 0; k < 2; ++k) {
            glBindFramebuffer(GL_FRAMEBUFFER, k == 0 ? directFramebuffer : indirectFramebuffer);
            glBindTextureUnit(4, reflection_[k].id());
            glDrawArrays(GL_TRIANGLES, 0, 3);
        }
        input.timers.end();
    }

    void dumpVdb(const std::string& path) const override {
        if (diffuse_) diffuse_->dumpVdb(path);
        else GiTechnique::dumpVdb(path);
    }
    DebugDrawing debugView(const std::string& view, const DebugViewContext& context) const override {
        return diffuse_ ? diffuse_->debugView(view, context) : DebugDrawing{};
    }
    std::vector<TechniqueStat> stats() const override {
        std::vector<TechniqueStat> out = diffuse_ ? diffuse_->stats() : std::vector<TechniqueStat>{};
        out.push_back({"hybrid.pixels", double(pixels_), "pixels with a mirror-like lobe"});
        out.push_back({"hybrid.glossy_pixels", double(glossyPixels_), "pixels with a traced glossy lobe"});
        out.push_back({"hybrid.rays", double(rays_), "rays"});
        out.push_back({"hybrid.layers", double(active_), "layers of surfaces seen through them"});
        if (desc_.replayBare) {
            out.push_back({"hybrid.rays_per_s", raysPerSecond_, "rays/s (tracing and hit records, all threads)"});
            out.push_back({"hybrid.bare_rays_per_s", bareRaysPerSecond_, "rays/s (the same rays, Embree alone)"});
        }
        return out;
    }
    void trackConvergence() override {
        if (diffuse_) diffuse_->trackConvergence();
    }
    std::optional<double> lightStateChange() const override {
        return diffuse_ ? diffuse_->lightStateChange() : std::nullopt;
    }

private:
    // One frame's rays: the G-buffer read back (owned: the trace may outlive the frame) and what
    // tracing it found.
    struct TraceJob {
        std::vector<float> position, normal, albedo, emission;
        MirrorPathInput in;
        MirrorPaths paths;
        double traceMs = 0.0;
        tbb::task_group tasks;
        void trace(const RayTracer& tracer) {
            in.position = position.data();
            in.normal = normal.data();
            in.albedo = albedo.data();
            in.emission = emission.data();
            paths = traceMirrorPaths(tracer, in);
        }
    };

    static double millisecondsSince(std::chrono::steady_clock::time_point t) {
        return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
    }

    std::unique_ptr<TraceJob> readBack(const GBufferView& g, std::uint32_t frame) const {
        auto job = std::make_unique<TraceJob>();
        job->position = gl::readTexture(g.position, g.width, g.height, 4);
        job->normal = gl::readTexture(g.normal, g.width, g.height, 4);
        job->albedo = gl::readTexture(g.albedo, g.width, g.height, 4);
        job->emission = gl::readTexture(g.emission, g.width, g.height, 4);
        MirrorPathInput& in = job->in;
        in.width = g.width;
        in.height = g.height;
        in.eye = g.eye;
        in.depth = desc_.depth;
        in.frame = frame;
        in.glossyRoughness = desc_.glossyRoughness;
        in.glossyRays = desc_.glossyRays;
        return job;
    }

    // The logged rays of the last trace again through Embree alone, for the two rates.
    void replayBare(const MirrorPaths& paths, double tracedSeconds) {
        const std::vector<LoggedRay> logged = tracer_.stopLog();
        const auto t0 = std::chrono::steady_clock::now();
        tracer_.replayBare(logged);
        const double bare = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        raysPerSecond_ = tracedSeconds > 0.0 ? double(paths.rays) / tracedSeconds : 0.0;
        bareRaysPerSecond_ = bare > 0.0 ? double(logged.size()) / bare : 0.0;
    }

    void uploadPaths(const FrameInput& input, const MirrorPaths& paths, const GBufferView& g);

    HybridDesc desc_;
    std::unique_ptr<GiTechnique> diffuse_;
    RayTracer tracer_;
    gl::Program composite_, resolve_;
    std::vector<LayerTextures> layers_;
    gl::Handle emittedDirect_, emittedIndirect_;
    gl::Handle reflection_[2], reflectionFramebuffer_[2];  // the rays' light per pixel: direct, indirect
    GBufferView primary_;
    int width_ = 0, height_ = 0;
    std::size_t active_ = 0;
    std::vector<glm::ivec4> bounds_;  // per active layer
    glm::ivec4 emittedHeld_{0};       // as LayerTextures::held, for the emitted light's textures
    glm::vec3 eye_{0.0f};
    glm::mat4 viewProjection_{1.0f};
    std::size_t pixels_ = 0, glossyPixels_ = 0;
    std::uint64_t rays_ = 0;
    double raysPerSecond_ = 0.0, bareRaysPerSecond_ = 0.0;
    std::unique_ptr<TraceJob> pending_;  // hybrid.overlap: the next frame's rays, being traced
};

}  // namespace

void HybridTechnique::uploadPaths(const FrameInput& input, const MirrorPaths& paths, const GBufferView& g) {
    pixels_ = paths.pixels;
    glossyPixels_ = paths.glossyPixels;
    rays_ = paths.rays;
    input.timers.begin("hybrid.upload");
    if (g.width != width_ || g.height != height_) {
        layers_.clear();
        width_ = g.width;
        height_ = g.height;
        emittedDirect_ = gl::createTexture(GL_TEXTURE_2D, GL_RGBA32F, width_, height_);
        emittedIndirect_ = gl::createTexture(GL_TEXTURE_2D, GL_RGBA32F, width_, height_);
        for (int k = 0; k < 2; ++k) {
            reflection_[k] = gl::createTexture(GL_TEXTURE_2D, GL_RGBA32F, width_, height_);
            reflectionFramebuffer_[k] = gl::createFramebuffer({reflection_[k].id()}, 0, "hybrid reflection target");
        }
        emittedHeld_ = glm::ivec4(0, 0, width_, height_);  // new textures: undefined everywhere
    }
    // Only the pixels with mirror-like lobes hold anything (a tenth of a 512^2 frame of the
    // mirror Cornell box): uploading whole frames took 16-23 ms of an H100 (docs/gpu.md).
    const glm::ivec4 emitted = boundingRegion(paths.emittedBounds, emittedHeld_);
    uploadRegion(emittedDirect_.id(), width_, emitted, paths.emittedDirect);
    uploadRegion(emittedIndirect_.id(), width_, emitted, paths.emittedIndirect);
    emittedHeld_ = paths.emittedBounds;
    for (std::size_t l = 0; l < paths.layers.size(); ++l) {
        const SecondaryLayer& layer = paths.layers[l];
        if (l == layers_.size()) {
            LayerTextures t;
            t.surfaces = uploadGBuffer(layer.position, layer.normal, layer.albedo, layer.emission, width_, height_, g.eye);
            t.viewOrigin = gl::createTexture(GL_TEXTURE_2D, GL_RGBA32F, width_, height_);
            t.weight = gl::createTexture(GL_TEXTURE_2D, GL_RGBA32F, width_, height_);
            t.held = glm::ivec4(0, 0, width_, height_);  // new textures: undefined everywhere
            layers_.push_back(std::move(t));
        }
        LayerTextures& t = layers_[l];
        const glm::ivec4 region = boundingRegion(layer.bounds, t.held);
        t.surfaces.refill(layer.position, layer.normal, layer.albedo, layer.emission, region);
        uploadRegion(t.viewOrigin.id(), width_, region, layer.viewOrigin);
        uploadRegion(t.weight.id(), width_, region, layer.weight);
        t.held = layer.bounds;
    }
    active_ = paths.layers.size();
    bounds_.clear();
    for (const SecondaryLayer& layer : paths.layers) bounds_.push_back(layer.bounds);
    eye_ = g.eye;
    viewProjection_ = g.viewProjection;
    primary_ = g;
    input.timers.end();
}

std::unique_ptr<GiTechnique> createHybridTechnique(const Scene& scene, const HybridDesc& desc,
                                                   std::unique_ptr<GiTechnique> diffuse) {
    return std::make_unique<HybridTechnique>(scene, desc, std::move(diffuse));
}

}  // namespace voxgi
