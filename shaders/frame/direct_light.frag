#version 450 core
// Adds one light sample's reflected radiance (W/(m^2 sr)) to the accumulation target.
// Light kinds: 0 point / quad sample (cube shadow), 1 spot (2D shadow), 2 directional (2D shadow).
#include "common/brdf.glsl"

uniform sampler2D uPosition;
uniform sampler2D uNormal;
uniform sampler2D uAlbedo;
uniform sampler2D uEmission;
uniform samplerCube uShadowCube;
uniform sampler2DShadow uShadow2D;

uniform int uKind;
uniform vec3 uEye;
uniform vec3 uLightPosition;
uniform vec3 uLightDirection;   // the way light travels (spot axis, sun direction)
uniform vec3 uLightColor;       // W/sr for point/spot/quad sample, W/m^2 for directional
uniform vec3 uEmitterNormal;    // quad samples: cosine emission about this normal; zero = isotropic
uniform vec2 uSpotCos;          // cos(outer), cos(inner)
uniform mat4 uShadowMatrix;     // world -> shadow texture space (2D maps)
uniform float uShadowTexel;     // world size of one shadow texel at unit distance (normal offset)

layout(location = 0) out vec4 outColor;

float cubeVisibility(vec3 p, vec3 n) {
    vec3 d = p - uLightPosition;
    float dist = length(d);
    vec3 offset = p + n * (2.0 * uShadowTexel * dist);
    vec3 dir = offset - uLightPosition;
    float stored = texture(uShadowCube, dir).r;
    return length(dir) <= stored * 1.002 ? 1.0 : 0.0;
}

float mapVisibility(vec3 p, vec3 n, float dist) {
    vec3 offset = p + n * (1.5 * uShadowTexel * dist);
    vec4 s = uShadowMatrix * vec4(offset, 1.0);
    s.xyz /= s.w;
    if (any(lessThan(s.xy, vec2(0.0))) || any(greaterThan(s.xy, vec2(1.0)))) return 1.0;
    vec2 texel = 1.0 / vec2(textureSize(uShadow2D, 0));
    float sum = 0.0;
    for (int y = -1; y <= 1; ++y)
        for (int x = -1; x <= 1; ++x) sum += texture(uShadow2D, vec3(s.xy + vec2(x, y) * texel, s.z - 1e-4));
    return sum / 9.0;
}

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    vec4 pos = texelFetch(uPosition, pixel, 0);
    if (pos.w == 0.0) { outColor = vec4(0.0); return; }
    vec4 nr = texelFetch(uNormal, pixel, 0);
    vec4 am = texelFetch(uAlbedo, pixel, 0);
    vec4 es = texelFetch(uEmission, pixel, 0);
    Surface s = Surface(am.rgb, nr.w, am.w, es.w);
    vec3 p = pos.xyz;
    vec3 n = normalize(nr.xyz);
    vec3 v = normalize(uEye - p);

    vec3 l;
    vec3 incident;  // irradiance at normal incidence (W/m^2) times visibility
    if (uKind == 2) {
        l = -uLightDirection;
        incident = uLightColor * mapVisibility(p, n, 1.0);
    } else {
        vec3 toLight = uLightPosition - p;
        float d2 = max(dot(toLight, toLight), 1e-12);
        float d = sqrt(d2);
        l = toLight / d;
        vec3 intensity = uLightColor;
        if (uKind == 1) {
            float c = dot(-l, uLightDirection);
            intensity *= smoothstep(uSpotCos.x, uSpotCos.y, c);
        }
        if (dot(uEmitterNormal, uEmitterNormal) > 0.0) intensity *= max(dot(uEmitterNormal, -l), 0.0);
        if (max(intensity.r, max(intensity.g, intensity.b)) <= 0.0) { outColor = vec4(0.0); return; }
        float vis = uKind == 1 ? mapVisibility(p, n, d) : cubeVisibility(p, n);
        incident = intensity / d2 * vis;
    }
    float nl = dot(n, l);
    if (nl <= 0.0) { outColor = vec4(0.0); return; }
    outColor = vec4(evalBrdf(s, n, v, l) * incident * nl, 1.0);
}
