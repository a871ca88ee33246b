// Structs shared with GLSL (std430); keep in sync with shaders/common/scene_data.glsl.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

namespace voxgi {

struct MaterialGpu {
    glm::vec4 albedo;
    glm::vec4 emission;
    float roughness;
    float metallic;
    float specular;
    std::int32_t textureLayer;
};
static_assert(sizeof(MaterialGpu) == 48, "std430 layout of MaterialGpu");

}  // namespace voxgi
