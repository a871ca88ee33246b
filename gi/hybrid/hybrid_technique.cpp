#include "gi/hybrid/hybrid_technique.h"

#include <chrono>

#include "gi/hybrid/mirror_paths.h"
#include "gi/raytrace/ray_tracer.h"
#include "gl/program.h"
#include "gl/resources.h"

namespace voxgi {

namespace {

// One layer's textures on the GPU: the G-buffer the frame lights, each pixel's viewer and
// weight, and the target the frame's passes add the layer's light into.
struct LayerTextures {
    gl::Handle position, normal, albedo, emission, viewOrigin, weight, light, lightFbo;
};

void upload(GLuint texture, int width, int height, const glm::vec4* data) {
    glTextureSubImage2D(texture, 0, 0, 0, width, height, GL_RGBA, GL_FLOAT, data);
}

class HybridTechnique final : public GiTechnique {
public:
    HybridTechnique(const Scene& scene, const HybridDesc& desc, std::unique_ptr<GiTechnique> diffuse)
        : desc_(desc), diffuse_(std::move(diffuse)), tracer_(scene),
          composite_(gl::Program::graphics("frame/fullscreen.vert", "hybrid/composite.frag")) {}

    std::string name() const override { return "hybrid"; }

    void update(const FrameInput& input, const GBufferView& g) override {
        if (diffuse_) diffuse_->update(input, g);
        active_ = 0;
        if (!input.plan.runs("hybrid.trace")) return;
        const auto t0 = std::chrono::steady_clock::now();
        const std::vector<float> position = gl::readTexture(g.position, g.width, g.height, 4);
        const std::vector<float> normal = gl::readTexture(g.normal, g.width, g.height, 4);
        const std::vector<float> albedo = gl::readTexture(g.albedo, g.width, g.height, 4);
        const std::vector<float> emission = gl::readTexture(g.emission, g.width, g.height, 4);
        MirrorPathInput in;
        in.width = g.width;
        in.height = g.height;
        in.position = position.data();
        in.normal = normal.data();
        in.albedo = albedo.data();
        in.emission = emission.data();
        in.eye = g.eye;
        in.depth = desc_.depth;
        in.frame = std::uint32_t(input.frameIndex);
        const MirrorPaths paths = traceMirrorPaths(tracer_, in);
        input.timers.addCpu("hybrid.trace",
                            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
        pixels_ = paths.pixels;
        rays_ = paths.rays;

        input.timers.begin("hybrid.upload");
        ensureSize(g.width, g.height, paths.layers.size());
        upload(emittedDirect_.id(), g.width, g.height, paths.emittedDirect.data());
        upload(emittedIndirect_.id(), g.width, g.height, paths.emittedIndirect.data());
        std::vector<glm::vec4> target(std::size_t(g.width) * std::size_t(g.height));
        const float zero[4] = {0, 0, 0, 0};
        for (std::size_t l = 0; l < paths.layers.size(); ++l) {
            const SecondaryLayer& layer = paths.layers[l];
            LayerTextures& t = layers_[l];
            glm::vec4 shading::GBufferTexels::*parts[4] = {&shading::GBufferTexels::position, &shading::GBufferTexels::normal,
                                                          &shading::GBufferTexels::albedo, &shading::GBufferTexels::emission};
            const GLuint textures[4] = {t.position.id(), t.normal.id(), t.albedo.id(), t.emission.id()};
            for (int k = 0; k < 4; ++k) {
                for (std::size_t i = 0; i < target.size(); ++i) target[i] = layer.texels[i].*parts[k];
                upload(textures[k], g.width, g.height, target.data());
            }
            upload(t.viewOrigin.id(), g.width, g.height, layer.viewOrigin.data());
            upload(t.weight.id(), g.width, g.height, layer.weight.data());
            glClearNamedFramebufferfv(t.lightFbo.id(), GL_COLOR, 0, zero);
        }
        active_ = paths.layers.size();
        bounds_.clear();
        for (const SecondaryLayer& layer : paths.layers) bounds_.push_back(layer.bounds);
        eye_ = g.eye;
        viewProjection_ = g.viewProjection;
        input.timers.end();
    }

    void applyIndirect(const FrameInput& input, const GBufferView& g) override {
        if (diffuse_) diffuse_->applyIndirect(input, g);
    }

    std::vector<SecondaryLayerView> secondaryLayers() const override {
        std::vector<SecondaryLayerView> out;
        for (std::size_t l = 0; l < active_; ++l) {
            const LayerTextures& t = layers_[l];
            SecondaryLayerView v;
            v.surfaces.position = t.position.id();
            v.surfaces.normal = t.normal.id();
            v.surfaces.albedo = t.albedo.id();
            v.surfaces.emission = t.emission.id();
            v.surfaces.width = width_;
            v.surfaces.height = height_;
            v.surfaces.eye = eye_;
            v.surfaces.viewProjection = viewProjection_;
            v.surfaces.viewOrigin = t.viewOrigin.id();
            v.lightFramebuffer = t.lightFbo.id();
            v.scissor = bounds_[l];
            out.push_back(v);
        }
        return out;
    }

    void composite(const FrameInput& input, GLuint directFramebuffer, GLuint indirectFramebuffer) override {
        if (!input.plan.runs("hybrid.composite") || width_ == 0) return;
        input.timers.begin("hybrid.composite");
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
        glEnable(GL_SCISSOR_TEST);
        for (std::size_t l = 0; l < active_; ++l) {
            glScissor(bounds_[l].x, bounds_[l].y, bounds_[l].z, bounds_[l].w);
            draw(indirectFramebuffer, layers_[l].light.id(), layers_[l].weight.id());
        }
        glDisable(GL_SCISSOR_TEST);
        draw(indirectFramebuffer, emittedIndirect_.id(), 0);
        draw(directFramebuffer, emittedDirect_.id(), 0);
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
        out.push_back({"hybrid.rays", double(rays_), "rays"});
        out.push_back({"hybrid.layers", double(active_), "layers of surfaces seen through them"});
        return out;
    }
    void trackConvergence() override {
        if (diffuse_) diffuse_->trackConvergence();
    }
    std::optional<double> lightStateChange() const override {
        return diffuse_ ? diffuse_->lightStateChange() : std::nullopt;
    }

private:
    void ensureSize(int width, int height, std::size_t layers) {
        if (width != width_ || height != height_) {
            layers_.clear();
            width_ = width;
            height_ = height;
            emittedDirect_ = gl::createTexture(GL_TEXTURE_2D, GL_RGBA32F, width, height);
            emittedIndirect_ = gl::createTexture(GL_TEXTURE_2D, GL_RGBA32F, width, height);
        }
        while (layers_.size() < layers) {
            LayerTextures t;
            t.position = gl::createTexture(GL_TEXTURE_2D, GL_RGBA32F, width, height);
            t.normal = gl::createTexture(GL_TEXTURE_2D, GL_RGBA16F, width, height);
            t.albedo = gl::createTexture(GL_TEXTURE_2D, GL_RGBA16F, width, height);
            t.emission = gl::createTexture(GL_TEXTURE_2D, GL_RGBA32F, width, height);
            t.viewOrigin = gl::createTexture(GL_TEXTURE_2D, GL_RGBA32F, width, height);
            t.weight = gl::createTexture(GL_TEXTURE_2D, GL_RGBA32F, width, height);
            t.light = gl::createTexture(GL_TEXTURE_2D, GL_RGBA32F, width, height);
            t.lightFbo = gl::createFramebuffer({t.light.id()}, 0, "hybrid layer light");
            layers_.push_back(std::move(t));
        }
    }

    HybridDesc desc_;
    std::unique_ptr<GiTechnique> diffuse_;
    RayTracer tracer_;
    gl::Program composite_;
    std::vector<LayerTextures> layers_;
    gl::Handle emittedDirect_, emittedIndirect_;
    int width_ = 0, height_ = 0;
    std::size_t active_ = 0;
    std::vector<glm::ivec4> bounds_;  // per active layer
    glm::vec3 eye_{0.0f};
    glm::mat4 viewProjection_{1.0f};
    std::size_t pixels_ = 0;
    std::uint64_t rays_ = 0;
};

}  // namespace

std::unique_ptr<GiTechnique> createHybridTechnique(const Scene& scene, const HybridDesc& desc,
                                                   std::unique_ptr<GiTechnique> diffuse) {
    return std::make_unique<HybridTechnique>(scene, desc, std::move(diffuse));
}

}  // namespace voxgi
