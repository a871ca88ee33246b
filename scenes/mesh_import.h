// Mesh files through assimp: OBJ+MTL (diffuse textures), glTF 2.0, PLY and the other formats
// assimp reads. Results are appended to a scene with the given transform applied.
#pragma once

#include <string>

#include <glm/glm.hpp>

#include "scenes/scene.h"

namespace voxgi {

struct MeshImportStats {
    std::size_t triangles = 0;
    std::size_t materials = 0;
    std::size_t textures = 0;
};

// Throws InputError naming the file when assimp cannot read it or it holds no triangles.
// `materialOverride` >= 0 assigns that scene material to every triangle instead of the file's.
MeshImportStats importMeshFile(const std::string& path, const glm::mat4& transform, Scene& scene,
                               int materialOverride = -1);

// Loads an image (PNG, JPEG, TGA...) as an sRGB texture; throws InputError on failure.
Texture loadTexture(const std::string& path);

}  // namespace voxgi
