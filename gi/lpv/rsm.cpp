#include "gi/lpv/rsm.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "gl/program.h"
#include "gl/resources.h"
#include "gl/scene_gpu.h"

namespace voxgi {

namespace {

glm::vec3 anyUp(glm::vec3 d) { return std::abs(d.y) < 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0); }

// How one face of a light is rasterized.
struct FaceView {
    glm::mat4 viewProjection;
    bool orthographic;  // the sun's map; the others are perspective from a point (point, spot, quad)
    glm::vec3 origin, forward;
    float tanHalf, orthoTexelArea;
};

// Quad lights are rendered from their centre: the light model sees them through that point.
constexpr glm::vec2 kQuadCentre{0.5f, 0.5f};

std::vector<FaceView> faceViews(const Scene& scene, const Light& light, int size) {
    Bounds b = scene.bounds();
    glm::vec3 center = b.valid() ? b.center() : glm::vec3(0.0f);
    float radius = b.valid() ? std::max(0.5f * glm::length(b.extent()), 1e-6f) : 1.0f;
    std::vector<FaceView> views;
    if (light.type == LightType::Directional) {
        glm::vec3 eye = center - light.direction * (2.0f * radius);
        glm::mat4 view = glm::lookAt(eye, center, anyUp(light.direction));
        glm::mat4 proj = glm::ortho(-radius, radius, -radius, radius, 0.0f, 4.0f * radius);
        float texel = 2.0f * radius / float(size);
        views.push_back({proj * view, true, eye, light.direction, 0.0f, texel * texel});
        return views;
    }
    glm::vec3 origin = light.type == LightType::Quad ? light.quadCenter() + light.quadNormal() * (1e-4f * radius)
                                                     : light.position;
    float nearPlane = 1e-4f * radius, farPlane = glm::length(origin - center) + 2.0f * radius;
    if (light.type == LightType::Spot) {
        float half = glm::radians(light.outerConeDegrees) + 0.02f;
        glm::mat4 view = glm::lookAt(origin, origin + light.direction, anyUp(light.direction));
        glm::mat4 proj = glm::perspective(2.0f * half, 1.0f, nearPlane, farPlane);
        views.push_back({proj * view, false, origin, light.direction, std::tan(half), 0.0f});
        return views;
    }
    // Point lights and quad lights: six 90-degree faces (a quad's back faces receive nothing).
    static const glm::vec3 dirs[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    glm::mat4 proj = glm::perspective(glm::radians(90.0f), 1.0f, nearPlane, farPlane);
    for (const glm::vec3& d : dirs) {
        if (light.type == LightType::Quad && glm::dot(d, light.quadNormal()) < -0.99f) continue;
        glm::mat4 view = glm::lookAt(origin, origin + d, anyUp(d));
        views.push_back({proj * view, false, origin, d, 1.0f, 0.0f});
    }
    return views;
}

}  // namespace

RsmTargets::RsmTargets(int size) {
    position = gl::createTexture(GL_TEXTURE_2D, GL_RGBA32F, size, size);
    normal = gl::createTexture(GL_TEXTURE_2D, GL_RGBA32F, size, size);
    flux = gl::createTexture(GL_TEXTURE_2D, GL_RGBA32F, size, size);
    albedo = gl::createTexture(GL_TEXTURE_2D, GL_RGBA32F, size, size);
    depth = gl::createTexture(GL_TEXTURE_2D, GL_DEPTH_COMPONENT32F, size, size);
    fbo = gl::createFramebuffer({position.id(), normal.id(), flux.id(), albedo.id()}, depth.id(), "reflective shadow map");
}

SurfelSource readSurfels(const RsmFace& face) {
    const int size = face.size;
    std::vector<float> p = gl::readTexture(face.position, size, size, 4);
    std::vector<float> n = gl::readTexture(face.normal, size, size, 4);
    std::vector<float> f = gl::readTexture(face.flux, size, size, 4);
    std::vector<float> a = gl::readTexture(face.albedo, size, size, 4);
    const std::size_t texels = std::size_t(size) * std::size_t(size);
    std::size_t hits = 0;
    for (std::size_t i = 0; i < texels; ++i) hits += n[4 * i + 3] > 0.0f ? 1 : 0;
    SurfelSource source;
    source.surfels.reserve(hits);  // growing by push_back cost a third of a 4096^2 face's time
    for (std::size_t i = 0; i < texels; ++i) {
        if (n[4 * i + 3] <= 0.0f) continue;  // no surface in this texel
        Surfel s;
        s.position = {p[4 * i], p[4 * i + 1], p[4 * i + 2]};
        s.area = p[4 * i + 3];
        s.normal = {n[4 * i], n[4 * i + 1], n[4 * i + 2]};
        s.flux = {f[4 * i], f[4 * i + 1], f[4 * i + 2]};
        s.albedo = {a[4 * i], a[4 * i + 1], a[4 * i + 2]};
        s.toLight = face.orthographic ? face.toLight : glm::normalize(face.origin - s.position);
        source.surfels.push_back(s);
    }
    return source;
}

struct RsmRenderer::Impl {
    int size;
    gl::Program program;
    std::vector<std::unique_ptr<RsmTargets>> targets;  // grown to the most faces seen in one frame
    std::vector<RsmFace> faces;

    explicit Impl(int s) : size(s) { program = gl::Program::graphics("lpv/rsm.vert", "lpv/rsm.frag"); }

    RsmFace renderFace(std::size_t slot, const Scene& scene, const SceneGpu& gpu, const FaceView& v,
                       std::size_t lightIndex) {
        while (targets.size() <= slot) targets.push_back(std::make_unique<RsmTargets>(size));
        const RsmTargets& t = *targets[slot];
        glBindFramebuffer(GL_FRAMEBUFFER, t.fbo.id());
        glViewport(0, 0, size, size);
        const float zero[4] = {0, 0, 0, 0};
        for (int i = 0; i < 4; ++i) glClearBufferfv(GL_COLOR, i, zero);
        glClear(GL_DEPTH_BUFFER_BIT);
        glEnable(GL_DEPTH_TEST);
        glDisable(GL_BLEND);
        glDisable(GL_CULL_FACE);
        program.use();
        program.set("uViewProjection", v.viewProjection);
        program.set("uLight", int(lightIndex));
        program.set("uQuadSample", kQuadCentre);
        program.set("uFaceOrigin", v.origin);
        program.set("uFaceForward", v.forward);
        // Solid angle of one texel on the unit-distance image plane, before the cos^3 factor.
        float texel = 2.0f * v.tanHalf / float(size);
        program.set("uTexelSolidAngle", texel * texel);
        program.set("uOrthoTexelArea", v.orthoTexelArea);
        program.set("uTextures", 0);
        gpu.bind(0);
        gpu.draw();
        glBindFramebuffer(GL_FRAMEBUFFER, 0);

        RsmFace face;
        face.position = t.position.id();
        face.normal = t.normal.id();
        face.flux = t.flux.id();
        face.albedo = t.albedo.id();
        face.size = size;
        face.orthographic = v.orthographic;
        face.origin = v.origin;
        face.toLight = -scene.lights[lightIndex].direction;
        return face;
    }
};

RsmRenderer::RsmRenderer(int size) : impl_(std::make_unique<Impl>(size)) {}
RsmRenderer::~RsmRenderer() = default;

std::size_t rsmFaceCount(const Scene& scene) {
    std::size_t count = 0;
    for (const Light& light : scene.lights) count += faceViews(scene, light, 1).size();
    return count;
}

std::size_t RsmRenderer::facesPerBatch() const {
    // Four RGBA32F colour targets and a 32-bit depth buffer per texel.
    const double faceBytes = 68.0 * double(impl_->size) * double(impl_->size);
    return std::max<std::size_t>(1, std::size_t(256.0 * 1024.0 * 1024.0 / faceBytes));
}

const std::vector<RsmFace>& RsmRenderer::renderToTextures(const Scene& scene, const SceneGpu& gpu, std::size_t first,
                                                          std::size_t count) {
    impl_->faces.clear();
    std::size_t index = 0;
    for (std::size_t light = 0; light < scene.lights.size(); ++light)
        for (const FaceView& v : faceViews(scene, scene.lights[light], impl_->size)) {
            if (index >= first && index - first < count)
                impl_->faces.push_back(impl_->renderFace(impl_->faces.size(), scene, gpu, v, light));
            ++index;
        }
    return impl_->faces;
}

}  // namespace voxgi
