#version 450 core
// Adds the light the hybrid method's rays brought to each pixel (uReflection: the layers times
// their weights plus the emitters and sky the rays met) to the frame. Mirror-like pixels take
// theirs as it is; glossy pixels (shading::glossyLobe) take an edge-aware mean over their
// glossy neighbours: a Gaussian in pixels, stopped by the distance from the pixel's tangent
// plane (relative to its distance from the eye), by the angle between normals and by a
// different roughness. Each neighbour's light is divided by its own Fresnel term and the mean
// multiplied by the pixel's, so a metal's colour and texture stay sharp (docs/hybrid.md).
#include "common/brdf.glsl"
#include "common/gbuffer_textures.glsl"

uniform sampler2D uReflection;
uniform vec3 uEye;
uniform float uGlossyRoughness;
uniform int uRadius;

layout(location = 0) out vec4 outColor;

// The glossy lobe's Fresnel reflectance toward the eye, which the rays' weights carry.
vec3 specularAlbedo(GBufferSurface g) {
    vec3 f0 = mix(vec3(g.specular), g.albedo, g.metallic);
    return (1.0 - g.transmission) * fresnelSchlick(f0, max(dot(g.normal, normalize(uEye - g.position)), 0.0));
}

bool glossyAt(GBufferTexels t, out GBufferSurface g) {
    if (!gbufferHit(t.position)) return false;
    g = decodeGBuffer(t);
    return glossyLobe(g.roughness, g.metallic, g.specular, g.transmission, uGlossyRoughness);
}

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    vec3 own = texelFetch(uReflection, pixel, 0).rgb;
    GBufferSurface g;
    if (uRadius == 0 || !glossyAt(fetchGBuffer(pixel), g)) { outColor = vec4(own, 1.0); return; }
    vec3 albedo = specularAlbedo(g);
    float planeTolerance = 0.01 * length(uEye - g.position);
    float sigma = 0.5 * float(uRadius);
    ivec2 size = textureSize(uReflection, 0);
    vec3 sum = vec3(0.0);
    float weights = 0.0;
    for (int dy = -uRadius; dy <= uRadius; ++dy)
        for (int dx = -uRadius; dx <= uRadius; ++dx) {
            ivec2 q = pixel + ivec2(dx, dy);
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
            GBufferSurface h;
            if (!glossyAt(fetchGBuffer(q), h)) continue;
            vec3 qAlbedo = specularAlbedo(h);
            if (any(lessThanEqual(qAlbedo, vec3(0.0)))) continue;
            float plane = abs(dot(g.normal, h.position - g.position)) / planeTolerance;
            float w = exp(-0.5 * float(dx * dx + dy * dy) / (sigma * sigma) - plane * plane) *
                      pow(max(dot(g.normal, h.normal), 0.0), 64.0) *
                      exp(-abs(h.roughness - g.roughness) / max(0.1 * g.roughness, 1e-3));
            sum += w * texelFetch(uReflection, q, 0).rgb / qAlbedo;
            weights += w;
        }
    outColor = vec4(weights > 0.0 && all(greaterThan(albedo, vec3(0.0))) ? albedo * sum / weights : own, 1.0);
}
