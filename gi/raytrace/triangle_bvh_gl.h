// The scene's triangles on the GPU (shaders/common/triangle_bvh.glsl): DDGI's probe rays with
// ddgi.trace = bvh, the LPV apply's rays to its taps with lpv.tap_visibility. One storage
// buffer holds the hierarchy (gi/raytrace/triangle_bvh.h), the triangles' corners and, per
// triangle, what shading a hit needs: its vertex normals, its emission (none for a quad light's
// own geometry, which the direct pass draws) and its diffuse albedo averaged over the triangle
// (the texture's mip level whose texel spans the triangle, read at its centroid) where DDGI's
// CPU reference averages over each ray's cone.
#pragma once

#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "gl/program.h"
#include "gl/resources.h"

namespace voxgi {

struct Scene;
struct TriangleBvh;

// Four vec4 per triangle of `bvh`, in its leaf order: (n0, emission r), (n1, g), (n2, b),
// (diffuse albedo, 0); vertex normals zero where the mesh has none.
std::vector<glm::vec4> triangleSurfaces(const Scene& scene, const TriangleBvh& bvh);

class TriangleBvhGl {
public:
    // Uploads the hierarchy and surfaces once. Needs a current GL 4.5 context.
    TriangleBvhGl(const Scene& scene, const TriangleBvh& bvh);

    // Binds the buffer at `binding` (the shader's TRIANGLE_BVH_BINDING) and sets its section
    // offsets on `program`.
    void bind(const gl::Program& program, GLuint binding) const;
    std::size_t bytes() const { return bytes_; }

private:
    gl::Handle buffer_;
    int corners_ = 0, surfaces_ = 0;
    std::size_t bytes_ = 0;
};

}  // namespace voxgi
