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
// Tabulated: a bilinear lookup decodes 12 values, and the path tracer does millions.
const std::array<float, 256>& srgbTable() {
    static const std::array<float, 256> table = [] {
        std::array<float, 256> t{};
        for (int i = 0; i < 256; ++i) {
            float c = float(i) / 255.0f;
            t[std::size_t(i)] = c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
        }
        return t;
    }();
    return table;
}
}  // namespace

float srgbToLinear(std::uint8_t code) { return srgbTable()[code]; }

const float* srgbDecodeTable() { return srgbTable().data(); }

std::uint8_t linearToSrgb(float linear) {
    // The code whose decoded value is nearest: the table is increasing, so search it and
    // compare the two neighbours (round trips are exact: linearToSrgb(srgbToLinear(c)) == c).
    const std::array<float, 256>& t = srgbTable();
    if (!(linear > 0.0f)) return 0;
    if (linear >= 1.0f) return 255;
    std::size_t hi = std::size_t(std::lower_bound(t.begin(), t.end(), linear) - t.begin());
    if (hi == 0) return 0;
    return std::uint8_t(linear - t[hi - 1] <= t[hi] - linear ? hi - 1 : hi);
}

namespace {
// Where a bilinear lookup lands: the texel left of and above uv (texel centres at (i + 0.5) /
// width, rows stored top first, v = 0 at the bottom) and the weights towards the next ones.
struct BilinearFootprint {
    int x0, y0;
    float fx, fy;
};
BilinearFootprint bilinearFootprint(int width, int height, glm::vec2 uv) {
    float x = (uv.x - std::floor(uv.x)) * float(width) - 0.5f;
    float y = (1.0f - (uv.y - std::floor(uv.y))) * float(height) - 0.5f;
    int x0 = int(std::floor(x)), y0 = int(std::floor(y));
    return {x0, y0, x - float(x0), y - float(y0)};
}
// Lookups step at most one texel past an edge, so one add or subtract wraps them (small mip
// levels wrap on most lookups: no division there); non-finite uvs take the modulo.
int wrapTexel(int i, int size) {
    if (unsigned(i) >= unsigned(size)) i = i < 0 ? i + size : i - size;
    if (unsigned(i) >= unsigned(size)) i = ((i % size) + size) % size;
    return i;
}
}  // namespace

glm::vec3 sampleSrgbBilinear(const std::uint8_t* rgba, int width, int height, glm::vec2 uv) {
    if (width <= 0 || height <= 0) return glm::vec3(1.0f);
    const BilinearFootprint f = bilinearFootprint(width, height, uv);
    const std::array<float, 256>& decode = srgbTable();
    auto texel = [&](int i, int j) {
        const std::uint8_t* p =
            &rgba[(std::size_t(wrapTexel(j, height)) * std::size_t(width) + std::size_t(wrapTexel(i, width))) * 4];
        return glm::vec3(decode[p[0]], decode[p[1]], decode[p[2]]);
    };
    glm::vec3 a = glm::mix(texel(f.x0, f.y0), texel(f.x0 + 1, f.y0), f.fx);
    glm::vec3 b = glm::mix(texel(f.x0, f.y0 + 1), texel(f.x0 + 1, f.y0 + 1), f.fx);
    return glm::mix(a, b, f.fy);
}

glm::vec3 Texture::sampleLinear(glm::vec2 uv) const {
    if (rgba.size() < std::size_t(width) * std::size_t(height) * 4) return glm::vec3(1.0f);
    return sampleSrgbBilinear(rgba.data(), width, height, uv);
}

void Texture::prefetch(glm::vec2 uv) const {
    // The prefetches stay in this body. GCC takes a function whose only effect is a
    // __builtin_prefetch for one without side effects and deletes the calls to it: with them
    // in a helper called from here, this function compiled to a bare `ret` and never
    // prefetched anything.
    if (width <= 0 || height <= 0 || rgba.size() < std::size_t(width) * std::size_t(height) * 4) return;
    const BilinearFootprint f = bilinearFootprint(width, height, uv);
    const std::size_t x = std::size_t(wrapTexel(f.x0, width));
    // The lower row first: of two prefetches issued back to back the second was the one still
    // missing when the lookup read it (Sponza's profile, docs/reference.md), and the lookup
    // reads row y0 first, so by then its line has had longest.
    for (int row : {f.y0 + 1, f.y0})
        __builtin_prefetch(&rgba[(std::size_t(wrapTexel(row, height)) * std::size_t(width) + x) * 4]);
}

bool operator==(const Light& a, const Light& b) {
    return a.type == b.type && a.name == b.name && a.position == b.position && a.direction == b.direction &&
           a.emission == b.emission && a.innerConeDegrees == b.innerConeDegrees && a.outerConeDegrees == b.outerConeDegrees &&
           a.angularDiameterDegrees == b.angularDiameterDegrees && a.edgeU == b.edgeU && a.edgeV == b.edgeV;
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

std::string Scene::quadLightMeshName(std::size_t light) const {
    return Mesh::kQuadLightMeshPrefix + (lights[light].name.empty() ? std::to_string(light) : lights[light].name);
}

const Mesh* Scene::quadLightMesh(std::size_t light) const {
    if (lights[light].type != LightType::Quad) return nullptr;
    const std::string name = quadLightMeshName(light);
    auto mesh = std::find_if(meshes.begin(), meshes.end(), [&](const Mesh& m) { return m.name == name; });
    return mesh == meshes.end() ? nullptr : &*mesh;
}

void Scene::addQuadLightGeometry() {
    for (std::size_t i = 0; i < lights.size(); ++i) {
        const Light& l = lights[i];
        if (l.type != LightType::Quad) continue;
        if (quadLightMesh(i)) continue;
        std::string meshName = quadLightMeshName(i);
        Material emitter;
        emitter.name = meshName;
        emitter.albedo = glm::vec3(0.0f);
        emitter.emission = l.emission;
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
