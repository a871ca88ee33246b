// Exact geometry of one triangle against one axis-aligned box: the conservative overlap test
// that decides occupancy and the clipped polygon that gives covered area and centroid.
#pragma once

#include <array>

#include <glm/glm.hpp>

namespace voxgi {

// Separating-axis test (13 axes: 3 box normals, the triangle normal, 9 edge cross products).
// Boxes are closed and grown by `slack` on every side, so a triangle lying exactly on a face
// or touching an edge counts as overlapping both neighbours: occupancy never has cracks.
bool triangleOverlapsBox(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c,
                         const glm::vec3& boxCenter, const glm::vec3& boxHalf, float slack = 0.0f);

// A convex polygon with at most 3 + 6 vertices (a triangle clipped by 6 planes).
struct ClipPolygon {
    std::array<glm::vec3, 12> v;
    int count = 0;
};

// Sutherland-Hodgman clip of the polygon to lo <= p[axis] <= hi (the upper plane first).
void clipToSlab(ClipPolygon& polygon, int axis, float lo, float hi);
// The triangle clipped to [lo, hi] (closed box): slabs along x, then y, then z.
ClipPolygon clipTriangleToBox(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c,
                              const glm::vec3& lo, const glm::vec3& hi);

// Area and area centroid of a planar convex polygon.
struct PolygonMoments {
    float area = 0.0f;
    glm::vec3 centroid{0.0f};
};
PolygonMoments polygonMoments(const ClipPolygon& polygon);

}  // namespace voxgi
