// The scene's triangles in a bounding-volume hierarchy laid out for GPU ray casting
// (shaders/common/triangle_bvh.glsl). Embree builds it (rtcBuildBVH, SAH, two children per
// node), so the GPU traverses the same kind of tree the CPU's rtcIntersect1 does, without a
// hand-written builder.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace voxgi {

struct Scene;

struct TriangleBvh {
    // Four vec4 per node, one pair per child: (lower corner, first), (upper corner, count) with
    // `first` and `count` ints stored as float bits. count > 0: a leaf of triangles [first,
    // first + count); count 0: an inner node at index `first`; first < 0: no child. Node 0 is
    // the root.
    std::vector<glm::vec4> nodes;
    // Three vec4 per triangle, in leaf order: its corners (w unused).
    std::vector<glm::vec4> corners;
    // Per triangle in leaf order: its index over all meshes (Scene order, mesh by mesh).
    std::vector<std::uint32_t> triangle;

    std::size_t nodeCount() const { return nodes.size() / 4; }
    std::size_t bytes() const { return (nodes.size() + corners.size()) * sizeof(glm::vec4) + triangle.size() * 4; }
};

// Bytes buildTriangleBvh needs at its peak (Embree's build primitives and nodes, and the layout).
double triangleBvhBytes(std::size_t triangles);

// Builds the hierarchy over every non-degenerate triangle of `scene` (at most 4 per leaf).
// Throws InputError when triangleBvhBytes exceeds the memory limit.
TriangleBvh buildTriangleBvh(const Scene& scene);

}  // namespace voxgi
