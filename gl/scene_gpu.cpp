#include "gl/scene_gpu.h"

#include <algorithm>
#include <cstring>
#include <vector>

#define STB_IMAGE_RESIZE_IMPLEMENTATION
#include <stb/stb_image_resize.h>

#include "shaders/shared/material.h"

namespace voxgi {

namespace {
struct Vertex {
    glm::vec3 position;
    glm::vec3 normal;
    glm::vec2 uv;
};
}  // namespace

gl::Handle uploadSkyTexture(const Sky& sky) {
    const int w = sky.tabulated() ? sky.width : 1, h = sky.tabulated() ? sky.height : 1;
    std::vector<glm::vec4> texels(std::size_t(w) * std::size_t(h), glm::vec4(0.0f));
    if (sky.enabled) {
        if (sky.tabulated())
            for (std::size_t i = 0; i < texels.size(); ++i) texels[i] = glm::vec4(sky.table[i], 0.0f);
        else
            texels[0] = glm::vec4(sky.radiance, 0.0f);
    }
    gl::Handle t = gl::createTexture(GL_TEXTURE_2D, GL_RGBA32F, w, h);
    glTextureSubImage2D(t.id(), 0, 0, 0, w, h, GL_RGBA, GL_FLOAT, texels.data());
    return t;
}

SceneGpu::SceneGpu(const Scene& scene) : sky_(uploadSkyTexture(scene.sky)) {
    std::vector<Vertex> vertices;
    std::vector<std::uint32_t> indices;
    std::vector<std::uint32_t> triMaterials;
    for (const Mesh& m : scene.meshes) {
        auto base = std::uint32_t(vertices.size());
        for (std::size_t i = 0; i < m.positions.size(); ++i)
            vertices.push_back({m.positions[i], m.normals.empty() ? glm::vec3(0.0f) : m.normals[i],
                                m.uvs.empty() ? glm::vec2(0.0f) : m.uvs[i]});
        for (std::uint32_t idx : m.indices) indices.push_back(base + idx);
        triMaterials.insert(triMaterials.end(), m.materialIds.begin(), m.materialIds.end());
    }
    triangles_ = triMaterials.size();

    using shading::MaterialGpu;
    std::vector<MaterialGpu> materials;
    for (const Material& m : scene.materials)
        materials.push_back({glm::vec4(m.albedo, m.transmission), glm::vec4(m.emission, 0.0f), m.roughness, m.metallic,
                             m.specular, m.albedoTexture});
    if (materials.empty()) materials.push_back({glm::vec4(0.8f), glm::vec4(0.0f), 1.0f, 0.0f, 0.0f, -1});

    vertices_ = gl::createBuffer(vertices.size() * sizeof(Vertex), vertices.data(), 0);
    indices_ = gl::createBuffer(indices.size() * sizeof(std::uint32_t), indices.data(), 0);
    materials_ = gl::createBuffer(materials.size() * sizeof(MaterialGpu), materials.data(), 0);
    triangleMaterials_ = gl::createBuffer(triMaterials.size() * sizeof(std::uint32_t), triMaterials.data(), 0);

    vao_ = gl::createVertexArray();
    GLuint vao = vao_.id();
    glVertexArrayVertexBuffer(vao, 0, vertices_.id(), 0, sizeof(Vertex));
    glVertexArrayElementBuffer(vao, indices_.id());
    const GLuint offsets[3] = {offsetof(Vertex, position), offsetof(Vertex, normal), offsetof(Vertex, uv)};
    const GLint sizes[3] = {3, 3, 2};
    for (GLuint a = 0; a < 3; ++a) {
        glEnableVertexArrayAttrib(vao, a);
        glVertexArrayAttribFormat(vao, a, sizes[a], GL_FLOAT, GL_FALSE, offsets[a]);
        glVertexArrayAttribBinding(vao, a, 0);
    }

    const int layers = std::max<int>(1, int(scene.textures.size()));
    const int levels = 10;  // 512 -> 1
    textures_ = gl::createTexture(GL_TEXTURE_2D_ARRAY, GL_SRGB8_ALPHA8, kTextureSize, kTextureSize, layers, levels);
    glTextureParameteri(textures_.id(), GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(textures_.id(), GL_TEXTURE_WRAP_T, GL_REPEAT);
    std::vector<std::uint8_t> resized(std::size_t(kTextureSize) * kTextureSize * 4, 255);
    for (std::size_t i = 0; i < scene.textures.size(); ++i) {
        const Texture& t = scene.textures[i];
        stbir_resize_uint8_srgb(t.rgba.data(), t.width, t.height, 0, resized.data(), kTextureSize, kTextureSize, 0, 4,
                                3, 0);
        glTextureSubImage3D(textures_.id(), 0, 0, 0, GLint(i), kTextureSize, kTextureSize, 1, GL_RGBA,
                            GL_UNSIGNED_BYTE, resized.data());
    }
    if (scene.textures.empty())
        glTextureSubImage3D(textures_.id(), 0, 0, 0, 0, kTextureSize, kTextureSize, 1, GL_RGBA, GL_UNSIGNED_BYTE,
                            resized.data());
    glGenerateTextureMipmap(textures_.id());
    updateLights(scene.lights);
}

void SceneGpu::bind(GLuint textureUnit) const {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, materials_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, triangleMaterials_.id());
    bindLights();
    glBindTextureUnit(textureUnit, textures_.id());
}

void SceneGpu::bindLights() const { glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, lights_.id()); }

void SceneGpu::updateLights(const std::vector<Light>& lights) {
    std::vector<shading::PackedLight> packed;
    for (const Light& l : lights) packed.push_back(shading::packLight(l));
    const std::size_t bytes = packed.size() * sizeof(shading::PackedLight);
    const bool same = lights_ && packed.size() == packedLights_.size() &&
                      std::memcmp(packed.data(), packedLights_.data(), bytes) == 0;
    if (!same) {
        // GL buffers cannot be empty: a scene without lights binds room for one, never read.
        if (!lights_ || packed.size() != packedLights_.size())
            lights_ = gl::createBuffer(std::max<std::size_t>(bytes, sizeof(shading::PackedLight)));
        if (bytes > 0) glNamedBufferSubData(lights_.id(), 0, GLsizeiptr(bytes), packed.data());
        packedLights_ = std::move(packed);
    }
}

void SceneGpu::draw() const {
    glBindVertexArray(vao_.id());
    glDrawElements(GL_TRIANGLES, GLsizei(triangles_ * 3), GL_UNSIGNED_INT, nullptr);
}

}  // namespace voxgi
