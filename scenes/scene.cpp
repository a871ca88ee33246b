#include "scenes/scene.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "scenes/primitives.h"

namespace voxgi {

glm::mat4 Camera::view() const { return glm::lookAt(eye, target, up); }

glm::mat4 Camera::projection() const {
    return glm::perspective(glm::radians(fovYDegrees), aspect(), nearPlane, farPlane);
}

namespace {
float srgbToLinear(std::uint8_t v) {
    // Tabulated: a bilinear lookup decodes 12 values, and the path tracer does millions.
    static const std::array<float, 256> table = [] {
        std::array<float, 256> t{};
        for (int i = 0; i < 256; ++i) {
            float c = float(i) / 255.0f;
            t[std::size_t(i)] = c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
        }
        return t;
    }();
    return table[v];
}
}  // namespace

glm::vec3 Texture::sampleLinear(glm::vec2 uv) const {
    if (width <= 0 || height <= 0) return glm::vec3(1.0f);
    // Texel centres at (i + 0.5) / width; rows stored top first, v = 0 is the bottom.
    float x = (uv.x - std::floor(uv.x)) * float(width) - 0.5f;
    float y = (1.0f - (uv.y - std::floor(uv.y))) * float(height) - 0.5f;
    int x0 = int(std::floor(x)), y0 = int(std::floor(y));
    float fx = x - float(x0), fy = y - float(y0);
    auto texel = [&](int i, int j) {
        // Lookups step at most one texel past an edge: wrap without dividing when inside.
        if (unsigned(i) >= unsigned(width)) i = ((i % width) + width) % width;
        if (unsigned(j) >= unsigned(height)) j = ((j % height) + height) % height;
        const std::uint8_t* p = &rgba[(std::size_t(j) * std::size_t(width) + std::size_t(i)) * 4];
        return glm::vec3(srgbToLinear(p[0]), srgbToLinear(p[1]), srgbToLinear(p[2]));
    };
    glm::vec3 a = glm::mix(texel(x0, y0), texel(x0 + 1, y0), fx);
    glm::vec3 b = glm::mix(texel(x0, y0 + 1), texel(x0 + 1, y0 + 1), fx);
    return glm::mix(a, b, fy);
}

Bounds Scene::bounds() const {
    Bounds b;
    for (const Mesh& m : meshes)
        for (const glm::vec3& p : m.positions) b.extend(p);
    return b;
}

std::size_t Scene::triangleCount() const {
    std::size_t n = 0;
    for (const Mesh& m : meshes) n += m.triangleCount();
    return n;
}

bool Scene::hasGlossyOrRefractive() const {
    return std::any_of(materials.begin(), materials.end(), [](const Material& m) {
        return m.transmission > 0.0f || ((m.metallic > 0.0f || m.specular > 0.0f) && m.roughness < 0.5f);
    });
}

void Scene::addQuadLightGeometry() {
    for (std::size_t i = 0; i < lights.size(); ++i) {
        const Light& l = lights[i];
        if (l.type != LightType::Quad) continue;
        std::string meshName = "quad_light_" + (l.name.empty() ? std::to_string(i) : l.name);
        bool present = std::any_of(meshes.begin(), meshes.end(),
                                   [&](const Mesh& m) { return m.name == meshName; });
        if (present) continue;
        Material emitter;
        emitter.name = meshName;
        emitter.albedo = glm::vec3(0.0f);
        emitter.emission = l.color;
        materials.push_back(emitter);
        std::uint32_t id = std::uint32_t(materials.size() - 1);
        Mesh quad = makeQuad({l.position, l.position + l.edgeU, l.position + l.edgeU + l.edgeV,
                              l.position + l.edgeV},
                             id);
        quad.name = meshName;
        meshes.push_back(std::move(quad));
    }
}

}  // namespace voxgi
