#include "gi/raytrace/triangle_bvh_gl.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>

#include <tbb/parallel_for.h>

#include "gi/raytrace/texture_pyramid.h"
#include "gi/raytrace/triangle_bvh.h"
#include "scenes/scene.h"
#include "shaders/shared/material.h"

namespace voxgi {

std::vector<glm::vec4> triangleSurfaces(const Scene& scene, const TriangleBvh& bvh) {
    std::vector<std::size_t> meshFirst;  // first global triangle of each mesh
    std::size_t total = 0;
    for (const Mesh& m : scene.meshes) {
        meshFirst.push_back(total);
        total += m.triangleCount();
    }
    std::vector<std::unique_ptr<TexturePyramid>> pyramids(scene.textures.size());
    tbb::parallel_for(std::size_t(0), scene.textures.size(),
                      [&](std::size_t i) { pyramids[i] = std::make_unique<TexturePyramid>(scene.textures[i]); });
    std::vector<glm::vec4> out(4 * bvh.triangle.size());
    tbb::parallel_for(std::size_t(0), bvh.triangle.size(), [&](std::size_t slot) {
        const std::size_t global = bvh.triangle[slot];
        const std::size_t m = std::size_t(std::upper_bound(meshFirst.begin(), meshFirst.end(), global) - meshFirst.begin()) - 1;
        const Mesh& mesh = scene.meshes[m];
        const std::size_t t = global - meshFirst[m];
        const std::uint32_t* tri = &mesh.indices[3 * t];
        const Material& material = scene.materials[mesh.materialIds[t]];
        const glm::vec3 emission = material.isEmissive() && !mesh.isQuadLightGeometry() ? material.emission : glm::vec3(0.0f);
        glm::vec3 albedo = material.albedo;
        if (material.albedoTexture >= 0 && !mesh.uvs.empty()) {
            const TexturePyramid& pyramid = *pyramids[std::size_t(material.albedoTexture)];
            const glm::vec3 p0 = mesh.positions[tri[0]], p1 = mesh.positions[tri[1]], p2 = mesh.positions[tri[2]];
            const glm::vec2 t0 = mesh.uvs[tri[0]], t1 = mesh.uvs[tri[1]], t2 = mesh.uvs[tri[2]];
            // Texels across the triangle: texels per unit length times its size.
            const float across = triangleTexelScale(p0, p1, p2, t0, t1, t2, 1, 1) * pyramid.texelScale() *
                                 std::sqrt(0.5f * glm::length(glm::cross(p1 - p0, p2 - p0)));
            albedo *= pyramid.sample((t0 + t1 + t2) / 3.0f, pyramid.levelForFootprint(across));
        }
        albedo = shading::diffuseAlbedo(albedo, material.metallic, material.specular, material.transmission);
        for (int k = 0; k < 3; ++k)
            out[4 * slot + std::size_t(k)] =
                glm::vec4(mesh.normals.empty() ? glm::vec3(0.0f) : mesh.normals[tri[k]], emission[k]);
        out[4 * slot + 3] = glm::vec4(albedo, 0.0f);
    });
    return out;
}

TriangleBvhGl::TriangleBvhGl(const Scene& scene, const TriangleBvh& bvh) {
    const std::vector<glm::vec4> surfaces = triangleSurfaces(scene, bvh);
    const std::size_t vec4s = bvh.nodes.size() + bvh.corners.size() + surfaces.size();
    if (vec4s > std::size_t(0x7FFFFFFF)) throw std::runtime_error("triangle BVH: too large for 32-bit indices");
    corners_ = int(bvh.nodes.size());
    surfaces_ = corners_ + int(bvh.corners.size());
    bytes_ = vec4s * sizeof(glm::vec4);
    buffer_ = gl::createBuffer(bytes_, nullptr, GL_DYNAMIC_STORAGE_BIT);
    glNamedBufferSubData(buffer_.id(), 0, GLsizeiptr(bvh.nodes.size() * sizeof(glm::vec4)), bvh.nodes.data());
    glNamedBufferSubData(buffer_.id(), GLintptr(std::size_t(corners_) * sizeof(glm::vec4)),
                         GLsizeiptr(bvh.corners.size() * sizeof(glm::vec4)), bvh.corners.data());
    glNamedBufferSubData(buffer_.id(), GLintptr(std::size_t(surfaces_) * sizeof(glm::vec4)),
                         GLsizeiptr(surfaces.size() * sizeof(glm::vec4)), surfaces.data());
}

void TriangleBvhGl::bind(const gl::Program& program, GLuint binding) const {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, buffer_.id());
    program.set("uBvhCorners", corners_);
    program.set("uBvhSurfaces", surfaces_);
}

}  // namespace voxgi
