// Built-in shapes for scenes that need no mesh file. All return world-space triangles with
// outward normals and the given material on every triangle.
#pragma once

#include <array>

#include <glm/glm.hpp>

#include "scenes/scene.h"

namespace voxgi {

// A planar quad c0 c1 c2 c3 (counter-clockwise seen from the front).
Mesh makeQuad(const std::array<glm::vec3, 4>& corners, std::uint32_t material);
// An axis-aligned unit box [-0.5, 0.5]^3 mapped through `transform`.
Mesh makeBox(const glm::mat4& transform, std::uint32_t material, bool inwardNormals = false);
// A UV sphere mapped through `transform`.
Mesh makeSphere(const glm::mat4& transform, std::uint32_t material, int segments = 32,
                bool inwardNormals = false);
// Polygons (triangles or larger convex faces, fanned) over shared vertices.
Mesh makePolygons(const std::vector<glm::vec3>& vertices,
                  const std::vector<std::vector<std::uint32_t>>& faces, std::uint32_t material);

}  // namespace voxgi
