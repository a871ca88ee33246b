#include "gi/lpv/rsm.h"

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "render/gl/program.h"
#include "render/gl/resources.h"
#include "render/gl/scene_gpu.h"

namespace voxgi {

namespace {
glm::vec3 anyUp(glm::vec3 d) { return std::abs(d.y) < 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0); }
}  // namespace

struct RsmRenderer::Impl {
    int size;
    gl::Program program;
    gl::Handle fbo, position, normal, flux, albedo, depth;

    explicit Impl(int s) : size(s) {
        program = gl::Program::graphics("lpv/rsm.vert", "lpv/rsm.frag");
        position = gl::createTexture(GL_TEXTURE_2D, GL_RGBA32F, size, size);
        normal = gl::createTexture(GL_TEXTURE_2D, GL_RGBA32F, size, size);
        flux = gl::createTexture(GL_TEXTURE_2D, GL_RGBA32F, size, size);
        albedo = gl::createTexture(GL_TEXTURE_2D, GL_RGBA32F, size, size);
        depth = gl::createTexture(GL_TEXTURE_2D, GL_DEPTH_COMPONENT32F, size, size);
        fbo = gl::createFramebuffer({position.id(), normal.id(), flux.id(), albedo.id()}, depth.id(),
                                    "reflective shadow map");
    }

    // kind: 0 perspective point-like (point, spot, quad), 2 orthographic (directional)
    SurfelSource renderFace(const SceneGpu& gpu, const glm::mat4& viewProjection, int kind, const Light& light,
                            glm::vec3 origin, glm::vec3 forward, float tanHalf, float orthoTexelArea) {
        glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
        glViewport(0, 0, size, size);
        const float zero[4] = {0, 0, 0, 0};
        for (int i = 0; i < 4; ++i) glClearBufferfv(GL_COLOR, i, zero);
        glClear(GL_DEPTH_BUFFER_BIT);
        glEnable(GL_DEPTH_TEST);
        glDisable(GL_BLEND);
        glDisable(GL_CULL_FACE);
        program.use();
        program.set("uViewProjection", viewProjection);
        program.set("uKind", kind);
        program.set("uLightPosition", origin);
        program.set("uLightForward", forward);
        program.set("uLightDirection", light.direction);
        program.set("uLightColor", light.type == LightType::Quad ? light.color * light.area() : light.color);
        program.set("uEmitterNormal", light.type == LightType::Quad ? light.quadNormal() : glm::vec3(0.0f));
        float outer = glm::radians(light.outerConeDegrees), inner = glm::radians(light.innerConeDegrees);
        program.set("uSpotCos", light.type == LightType::Spot ? glm::vec2(std::cos(outer), std::cos(inner))
                                                               : glm::vec2(-2.0f, -1.0f));
        // Solid angle of one texel on the unit-distance image plane, before the cos^3 factor.
        float texel = 2.0f * tanHalf / float(size);
        program.set("uTexelSolidAngle", texel * texel);
        program.set("uOrthoTexelArea", orthoTexelArea);
        program.set("uTextures", 0);
        gpu.bind(0);
        gpu.draw();

        std::vector<float> p = gl::readTexture(position.id(), size, size, 4);
        std::vector<float> n = gl::readTexture(normal.id(), size, size, 4);
        std::vector<float> f = gl::readTexture(flux.id(), size, size, 4);
        std::vector<float> a = gl::readTexture(albedo.id(), size, size, 4);
        SurfelSource source;
        for (std::size_t i = 0; i < std::size_t(size) * std::size_t(size); ++i) {
            if (n[4 * i + 3] <= 0.0f) continue;  // no surface in this texel
            Surfel s;
            s.position = {p[4 * i], p[4 * i + 1], p[4 * i + 2]};
            s.area = p[4 * i + 3];
            s.normal = {n[4 * i], n[4 * i + 1], n[4 * i + 2]};
            s.flux = {f[4 * i], f[4 * i + 1], f[4 * i + 2]};
            s.albedo = {a[4 * i], a[4 * i + 1], a[4 * i + 2]};
            s.toLight = kind == 2 ? -light.direction : glm::normalize(origin - s.position);
            source.surfels.push_back(s);
        }
        return source;
    }
};

RsmRenderer::RsmRenderer(int size) : impl_(std::make_unique<Impl>(size)) {}
RsmRenderer::~RsmRenderer() = default;

std::vector<SurfelSource> RsmRenderer::render(const Scene& scene, const SceneGpu& gpu, const Light& light) {
    Bounds b = scene.bounds();
    glm::vec3 center = b.valid() ? b.center() : glm::vec3(0.0f);
    float radius = b.valid() ? std::max(0.5f * glm::length(b.extent()), 1e-6f) : 1.0f;
    std::vector<SurfelSource> sources;
    if (light.type == LightType::Directional) {
        glm::vec3 eye = center - light.direction * (2.0f * radius);
        glm::mat4 view = glm::lookAt(eye, center, anyUp(light.direction));
        glm::mat4 proj = glm::ortho(-radius, radius, -radius, radius, 0.0f, 4.0f * radius);
        float texel = 2.0f * radius / float(impl_->size);
        sources.push_back(impl_->renderFace(gpu, proj * view, 2, light, eye, light.direction, 0.0f, texel * texel));
        return sources;
    }
    glm::vec3 origin = light.type == LightType::Quad ? light.quadCenter() + light.quadNormal() * (1e-4f * radius)
                                                     : light.position;
    float nearPlane = 1e-4f * radius, farPlane = glm::length(origin - center) + 2.0f * radius;
    if (light.type == LightType::Spot) {
        float half = glm::radians(light.outerConeDegrees) + 0.02f;
        glm::mat4 view = glm::lookAt(origin, origin + light.direction, anyUp(light.direction));
        glm::mat4 proj = glm::perspective(2.0f * half, 1.0f, nearPlane, farPlane);
        sources.push_back(impl_->renderFace(gpu, proj * view, 0, light, origin, light.direction, std::tan(half), 0.0f));
        return sources;
    }
    // Point lights and quad lights: six 90-degree faces (a quad's back faces receive nothing).
    static const glm::vec3 dirs[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    glm::mat4 proj = glm::perspective(glm::radians(90.0f), 1.0f, nearPlane, farPlane);
    for (const glm::vec3& d : dirs) {
        if (light.type == LightType::Quad && glm::dot(d, light.quadNormal()) < -0.99f) continue;
        glm::mat4 view = glm::lookAt(origin, origin + d, anyUp(d));
        sources.push_back(impl_->renderFace(gpu, proj * view, 0, light, origin, d, 1.0f, 0.0f));
    }
    return sources;
}

}  // namespace voxgi
