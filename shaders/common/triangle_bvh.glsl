// Ray casting through the scene's triangles (gi/raytrace/triangle_bvh.h, uploaded by
// gi/raytrace/triangle_bvh_gl.h as one buffer: nodes, then corners, then surfaces). Closest-hit and
// any-hit traversal of the two-child tree with a stack, nearer child first; a triangle is hit
// by the Moller-Trumbore test with Embree's barycentrics (u weighs the second corner, v the
// third). Define TRIANGLE_BVH_BINDING before including.
layout(std430, binding = TRIANGLE_BVH_BINDING) readonly buffer TriangleBvhData { vec4 bvhData[]; };

uniform int uBvhCorners;   // where the corners start in bvhData (three vec4 per triangle)
uniform int uBvhSurfaces;  // where the surfaces start (gi/raytrace/triangle_bvh_gl.h: four vec4 per triangle)

const int kBvhStackSize = 48;  // gi/raytrace/triangle_bvh.cpp's kMaxDepth

struct BvhHit {
    float t;
    int triangle;  // in leaf order
    vec2 uv;
};

// Entry distance into the box when the ray meets it within [tMin, tMax].
bool bvhBox(vec3 lo, vec3 hi, vec3 o, vec3 inv, float tMin, float tMax, out float tEnter) {
    vec3 a = (lo - o) * inv, b = (hi - o) * inv;
    vec3 near = min(a, b), far = max(a, b);
    tEnter = max(tMin, max(near.x, max(near.y, near.z)));
    return tEnter <= min(tMax, min(far.x, min(far.y, far.z)));
}

bool bvhTriangle(vec3 o, vec3 d, int k, float tMin, inout BvhHit hit) {
    vec3 v0 = bvhData[uBvhCorners + 3 * k].xyz;
    vec3 e1 = bvhData[uBvhCorners + 3 * k + 1].xyz - v0, e2 = bvhData[uBvhCorners + 3 * k + 2].xyz - v0;
    vec3 p = cross(d, e2);
    float det = dot(e1, p);
    if (det == 0.0) return false;
    float inv = 1.0 / det;
    vec3 s = o - v0;
    float u = dot(s, p) * inv;
    if (!(u >= 0.0 && u <= 1.0)) return false;
    vec3 q = cross(s, e1);
    float v = dot(d, q) * inv;
    if (!(v >= 0.0 && u + v <= 1.0)) return false;
    float t = dot(e2, q) * inv;
    if (!(t > tMin && t < hit.t)) return false;
    hit = BvhHit(t, k, vec2(u, v));
    return true;
}

// The nearest hit of o + t d for t in (tMin, tMax); with `anyHit` the first one found.
bool bvhTrace(vec3 o, vec3 d, float tMin, float tMax, bool anyHit, out BvhHit hit) {
    hit = BvhHit(tMax, -1, vec2(0.0));
    // Axes the ray does not move along: an infinite slab, never NaN (0 * inf).
    vec3 safe = mix(d, vec3(1e-30), equal(d, vec3(0.0)));
    vec3 inv = 1.0 / safe;
    int stack[kBvhStackSize];
    int top = 0, node = 0;
    for (;;) {
        vec4 lo0 = bvhData[4 * node], hi0 = bvhData[4 * node + 1];
        vec4 lo1 = bvhData[4 * node + 2], hi1 = bvhData[4 * node + 3];
        int first0 = floatBitsToInt(lo0.w), count0 = floatBitsToInt(hi0.w);
        int first1 = floatBitsToInt(lo1.w), count1 = floatBitsToInt(hi1.w);
        float t0, t1;
        bool in0 = first0 >= 0 && bvhBox(lo0.xyz, hi0.xyz, o, inv, tMin, hit.t, t0);
        bool in1 = first1 >= 0 && bvhBox(lo1.xyz, hi1.xyz, o, inv, tMin, hit.t, t1);
        if (in0 && count0 > 0) {
            for (int k = first0; k < first0 + count0; ++k)
                if (bvhTriangle(o, d, k, tMin, hit) && anyHit) return true;
            in0 = false;
        }
        if (in1 && count1 > 0) {
            for (int k = first1; k < first1 + count1; ++k)
                if (bvhTriangle(o, d, k, tMin, hit) && anyHit) return true;
            in1 = false;
        }
        if (in0 && in1) {
            bool nearFirst = t0 <= t1;
            if (top < kBvhStackSize) stack[top++] = nearFirst ? first1 : first0;
            node = nearFirst ? first0 : first1;
        } else if (in0 || in1) {
            node = in0 ? first0 : first1;
        } else {
            if (top == 0) break;
            node = stack[--top];
        }
    }
    return hit.triangle >= 0;
}

// The triangle's geometric normal (not unit), front side counter-clockwise as Embree's.
vec3 bvhGeometricNormal(int k) {
    vec3 v0 = bvhData[uBvhCorners + 3 * k].xyz;
    return cross(bvhData[uBvhCorners + 3 * k + 1].xyz - v0, bvhData[uBvhCorners + 3 * k + 2].xyz - v0);
}

// The interpolated vertex normal at the hit, unit (the geometric one without vertex normals).
vec3 bvhShadingNormal(BvhHit hit) {
    int s = uBvhSurfaces + 4 * hit.triangle;
    vec3 n = (1.0 - hit.uv.x - hit.uv.y) * bvhData[s].xyz + hit.uv.x * bvhData[s + 1].xyz + hit.uv.y * bvhData[s + 2].xyz;
    float len = length(n);
    if (!(len > 0.0)) {
        n = bvhGeometricNormal(hit.triangle);
        len = length(n);
    }
    return n / len;
}

// Diffuse albedo over the triangle (rgb) and emission (w of the first three records).
vec3 bvhAlbedo(int k) { return bvhData[uBvhSurfaces + 4 * k + 3].xyz; }
vec3 bvhEmission(int k) {
    int s = uBvhSurfaces + 4 * k;
    return vec3(bvhData[s].w, bvhData[s + 1].w, bvhData[s + 2].w);
}
