#include "scenes/primitives.h"

#include <cmath>

#include "shaders/shared/constants.h"

namespace voxgi {

namespace {
void addTriangle(Mesh& m, std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t mat) {
    m.indices.insert(m.indices.end(), {a, b, c});
    m.materialIds.push_back(mat);
}
}  // namespace

Mesh makeQuad(const std::array<glm::vec3, 4>& c, std::uint32_t material) {
    Mesh m;
    m.name = "quad";
    glm::vec3 n = glm::cross(c[1] - c[0], c[2] - c[0]);
    float len = glm::length(n);
    n = len > 0.0f ? n / len : glm::vec3(0.0f, 1.0f, 0.0f);
    const glm::vec2 uv[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (int i = 0; i < 4; ++i) {
        m.positions.push_back(c[i]);
        m.normals.push_back(n);
        m.uvs.push_back(uv[i]);
    }
    addTriangle(m, 0, 1, 2, material);
    addTriangle(m, 0, 2, 3, material);
    return m;
}

Mesh makeBox(const glm::mat4& transform, std::uint32_t material, bool inwardNormals) {
    Mesh m;
    m.name = "box";
    glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(transform)));
    // Each face: outward axis, then two tangent axes with cross(u, v) = axis.
    const glm::vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (const glm::vec3& n : axes) {
        glm::vec3 u = std::abs(n.y) > 0.5f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
        glm::vec3 v = glm::cross(n, u);
        u = glm::cross(v, n);
        glm::vec3 corners[4] = {0.5f * (n - u - v), 0.5f * (n + u - v), 0.5f * (n + u + v),
                                0.5f * (n - u + v)};
        std::uint32_t base = std::uint32_t(m.positions.size());
        glm::vec3 wn = glm::normalize(normalMatrix * n) * (inwardNormals ? -1.0f : 1.0f);
        const glm::vec2 uv[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
        for (int i = 0; i < 4; ++i) {
            m.positions.push_back(glm::vec3(transform * glm::vec4(corners[i], 1.0f)));
            m.normals.push_back(wn);
            m.uvs.push_back(uv[i]);
        }
        if (inwardNormals) {
            addTriangle(m, base, base + 2, base + 1, material);
            addTriangle(m, base, base + 3, base + 2, material);
        } else {
            addTriangle(m, base, base + 1, base + 2, material);
            addTriangle(m, base, base + 2, base + 3, material);
        }
    }
    return m;
}

Mesh makeSphere(const glm::mat4& transform, std::uint32_t material, int segments,
                bool inwardNormals) {
    Mesh m;
    m.name = "sphere";
    segments = segments < 4 ? 4 : segments;
    const int rings = segments / 2;
    glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(transform)));
    for (int r = 0; r <= rings; ++r) {
        float theta = shading::kPi * float(r) / float(rings);
        for (int s = 0; s <= segments; ++s) {
            float phi = 2.0f * shading::kPi * float(s) / float(segments);
            glm::vec3 p(std::sin(theta) * std::cos(phi), std::cos(theta),
                        std::sin(theta) * std::sin(phi));
            m.positions.push_back(glm::vec3(transform * glm::vec4(p, 1.0f)));
            m.normals.push_back(glm::normalize(normalMatrix * p) * (inwardNormals ? -1.0f : 1.0f));
            m.uvs.emplace_back(float(s) / float(segments), 1.0f - float(r) / float(rings));
        }
    }
    const std::uint32_t stride = std::uint32_t(segments + 1);
    for (int r = 0; r < rings; ++r)
        for (int s = 0; s < segments; ++s) {
            std::uint32_t a = std::uint32_t(r) * stride + std::uint32_t(s);
            std::uint32_t b = a + stride, c = a + 1, d = b + 1;
            // Outward winding: counter-clockwise seen from outside.
            if (r != 0) inwardNormals ? addTriangle(m, a, b, c, material) : addTriangle(m, a, c, b, material);
            if (r != rings - 1)
                inwardNormals ? addTriangle(m, c, b, d, material) : addTriangle(m, c, d, b, material);
        }
    return m;
}

Mesh makePolygons(const std::vector<glm::vec3>& vertices,
                  const std::vector<std::vector<std::uint32_t>>& faces, std::uint32_t material) {
    Mesh m;
    m.name = "polygons";
    // Vertices are duplicated per face so each face keeps a flat normal.
    for (const auto& face : faces) {
        if (face.size() < 3) continue;
        glm::vec3 n(0.0f);
        for (std::size_t i = 0; i < face.size(); ++i) {  // Newell's method: robust for quads
            const glm::vec3& a = vertices[face[i]];
            const glm::vec3& b = vertices[face[(i + 1) % face.size()]];
            n += glm::vec3((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x),
                           (a.x - b.x) * (a.y + b.y));
        }
        float len = glm::length(n);
        n = len > 0.0f ? n / len : glm::vec3(0, 1, 0);
        std::uint32_t base = std::uint32_t(m.positions.size());
        for (std::uint32_t idx : face) {
            m.positions.push_back(vertices[idx]);
            m.normals.push_back(n);
        }
        for (std::uint32_t i = 1; i + 1 < face.size(); ++i)
            addTriangle(m, base, base + i, base + i + 1, material);
    }
    return m;
}

}  // namespace voxgi
