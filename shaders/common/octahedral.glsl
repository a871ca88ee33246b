// Octahedral mapping and probe-tile layout; the same formulas as gi/octahedral/octahedral.h.
#ifndef VOXGI_OCTAHEDRAL_GLSL
#define VOXGI_OCTAHEDRAL_GLSL

vec2 octSignNotZero(vec2 v) { return vec2(v.x >= 0.0 ? 1.0 : -1.0, v.y >= 0.0 ? 1.0 : -1.0); }

vec2 octEncode(vec3 d) {
    float l1 = abs(d.x) + abs(d.y) + abs(d.z);
    if (!(l1 > 0.0)) return vec2(0.0);
    vec2 p = d.xy / l1;
    if (d.z < 0.0) p = (1.0 - abs(p.yx)) * octSignNotZero(p);
    return p;
}

vec3 octDecode(vec2 s) {
    vec3 d = vec3(s, 1.0 - abs(s.x) - abs(s.y));
    if (d.z < 0.0) d.xy = (1.0 - abs(d.yx)) * octSignNotZero(d.xy);
    return normalize(d);
}

vec3 octTexelDirection(ivec2 texel, int interior) {
    vec2 uv = (vec2(texel) + 0.5) / float(interior);
    return octDecode(uv * 2.0 - 1.0);
}

vec2 octTileCoordinate(vec3 direction, int interior) {
    vec2 uv = octEncode(direction) * 0.5 + 0.5;
    return vec2(1.0) + clamp(uv, 0.0, 1.0) * float(interior);
}

ivec2 octBorderSource(ivec2 t, int n) {
    bool left = t.x == 0, right = t.x == n + 1, bottom = t.y == 0, top = t.y == n + 1;
    if ((left || right) && (bottom || top)) return ivec2(left ? n : 1, bottom ? n : 1);
    if (bottom || top) return ivec2(n + 1 - t.x, bottom ? 1 : n);
    if (left || right) return ivec2(left ? 1 : n, n + 1 - t.y);
    return t;
}
#endif
