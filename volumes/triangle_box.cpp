#include "volumes/triangle_box.h"

#include <algorithm>
#include <cmath>

namespace voxgi {

namespace {

// Projections of the (box-centred) triangle and of the box onto `axis` are disjoint.
bool separatedOn(const glm::vec3& axis, const glm::vec3& v0, const glm::vec3& v1, const glm::vec3& v2,
                 const glm::vec3& half) {
    float p0 = glm::dot(axis, v0), p1 = glm::dot(axis, v1), p2 = glm::dot(axis, v2);
    float r = half.x * std::abs(axis.x) + half.y * std::abs(axis.y) + half.z * std::abs(axis.z);
    float lo = std::min(p0, std::min(p1, p2)), hi = std::max(p0, std::max(p1, p2));
    return lo > r || hi < -r;
}

}  // namespace

bool triangleOverlapsBox(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c,
                         const glm::vec3& boxCenter, const glm::vec3& boxHalf, float slack) {
    const glm::vec3 half = boxHalf + glm::vec3(slack);
    const glm::vec3 v0 = a - boxCenter, v1 = b - boxCenter, v2 = c - boxCenter;
    // Box face normals: the triangle's bounding box against the box.
    for (int k = 0; k < 3; ++k) {
        float lo = std::min(v0[k], std::min(v1[k], v2[k])), hi = std::max(v0[k], std::max(v1[k], v2[k]));
        if (lo > half[k] || hi < -half[k]) return false;
    }
    const glm::vec3 e0 = v1 - v0, e1 = v2 - v1, e2 = v0 - v2;
    // Triangle plane: all three vertices project to the same value, so one suffices.
    const glm::vec3 n = glm::cross(e0, e1);
    float r = half.x * std::abs(n.x) + half.y * std::abs(n.y) + half.z * std::abs(n.z);
    if (std::abs(glm::dot(n, v0)) > r) return false;
    // Edge x box-axis cross products. A zero axis (edge parallel to a box axis) never separates.
    const glm::vec3 edges[3] = {e0, e1, e2};
    for (const glm::vec3& e : edges) {
        const glm::vec3 axes[3] = {glm::vec3(0.0f, -e.z, e.y), glm::vec3(e.z, 0.0f, -e.x), glm::vec3(-e.y, e.x, 0.0f)};
        for (const glm::vec3& axis : axes)
            if (separatedOn(axis, v0, v1, v2, half)) return false;
    }
    return true;
}

namespace {

// Keeps the part of `in` with sign * (p[axis] - bound) <= 0.
void clipAgainst(const ClipPolygon& in, ClipPolygon& out, int axis, float bound, float sign) {
    out.count = 0;
    if (in.count == 0) return;
    for (int i = 0; i < in.count; ++i) {
        const glm::vec3& p = in.v[i];
        const glm::vec3& q = in.v[i + 1 == in.count ? 0 : i + 1];
        float dp = sign * (p[axis] - bound), dq = sign * (q[axis] - bound);
        if (dp <= 0.0f) out.v[out.count++] = p;
        if ((dp < 0.0f && dq > 0.0f) || (dp > 0.0f && dq < 0.0f)) {
            glm::vec3 x = p + (q - p) * (dp / (dp - dq));
            x[axis] = bound;  // exact on the plane, so neighbouring pieces share it
            out.v[out.count++] = x;
        }
    }
}

}  // namespace

void clipToSlab(ClipPolygon& polygon, int axis, float lo, float hi) {
    // Planes the polygon lies wholly inside of cannot cut it (most planes for small triangles);
    // clipping by them would return it unchanged.
    float pmin = 1e30f, pmax = -1e30f;
    for (int i = 0; i < polygon.count; ++i) {
        pmin = std::min(pmin, polygon.v[i][axis]);
        pmax = std::max(pmax, polygon.v[i][axis]);
    }
    ClipPolygon cut;
    if (pmax > hi) {
        clipAgainst(polygon, cut, axis, hi, 1.0f);
        if (pmin < lo) clipAgainst(cut, polygon, axis, lo, -1.0f);
        else polygon = cut;
    } else if (pmin < lo) {
        clipAgainst(polygon, cut, axis, lo, -1.0f);
        polygon = cut;
    }
}

ClipPolygon clipTriangleToBox(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c,
                              const glm::vec3& lo, const glm::vec3& hi) {
    ClipPolygon p;
    p.v[0] = a;
    p.v[1] = b;
    p.v[2] = c;
    p.count = 3;
    for (int axis = 0; axis < 3; ++axis) clipToSlab(p, axis, lo[axis], hi[axis]);
    return p;
}

PolygonMoments polygonMoments(const ClipPolygon& polygon) {
    PolygonMoments m;
    if (polygon.count < 3) return m;
    // Fan from vertex 0; a convex fan's triangle areas weight their centroids.
    glm::vec3 weighted(0.0f);
    float twiceAreaSum = 0.0f;
    const glm::vec3& o = polygon.v[0];
    for (int i = 1; i + 1 < polygon.count; ++i) {
        float twiceArea = glm::length(glm::cross(polygon.v[i] - o, polygon.v[i + 1] - o));
        twiceAreaSum += twiceArea;
        weighted += twiceArea * (o + polygon.v[i] + polygon.v[i + 1]);
    }
    m.area = 0.5f * twiceAreaSum;
    m.centroid = twiceAreaSum > 0.0f ? weighted / (3.0f * twiceAreaSum) : o;
    return m;
}

}  // namespace voxgi
