#version 450 core
// The sky's bounce as one more reflective shadow map face (seed 002 section 5.3.7): the camera's
// G-buffer sampled on a square grid of uSize^2 texels, each a surfel reflecting the sky-volume
// irradiance it receives. Written like shaders/lpv/rsm.frag (position and area, normal, flux,
// albedo), so both LPV back ends inject it as they inject a light's face. The area is the
// texel's footprint, its solid angle from the eye times distance^2 over the cosine: near and far
// surfaces inject the flux they really reflect (the seed's distance scaling, made exact).
#include "common/gbuffer_textures.glsl"
#include "common/sky_volume.glsl"

uniform vec3 uEye;
uniform vec3 uForward;            // the camera's axis
uniform float uTexelSolidAngle;   // one texel's solid angle on the axis (the image plane at unit distance)
uniform int uSize;

layout(location = 0) out vec4 outPosition;  // xyz, w = surfel area (m^2)
layout(location = 1) out vec4 outNormal;    // xyz, w = 1 where a surface was hit
layout(location = 2) out vec4 outFlux;      // rgb reflected diffuse flux (W)
layout(location = 3) out vec4 outAlbedo;    // rgb diffuse albedo

void main() {
    vec2 at = (floor(gl_FragCoord.xy) + 0.5) / float(uSize);
    GBufferTexels t = fetchGBuffer(ivec2(at * vec2(textureSize(uPosition, 0))));
    outPosition = vec4(0.0);
    outNormal = vec4(0.0);
    outFlux = vec4(0.0);
    outAlbedo = vec4(0.0);
    if (!gbufferHit(t.position)) return;
    GBufferSurface s = decodeGBuffer(t);
    vec3 d = s.position - uEye;
    float dist = length(d);
    if (!(dist > 0.0)) return;
    vec3 w = d / dist;
    float c = max(dot(w, uForward), 1e-3);
    float area = uTexelSolidAngle * c * c * c * dist * dist / max(abs(dot(s.normal, w)), 0.05);
    vec3 diffuse = surfaceDiffuseAlbedo(s);
    outPosition = vec4(s.position, area);
    outNormal = vec4(s.normal, 1.0);
    outFlux = vec4(diffuse * skyVolumeIrradiance(s.position, s.normal) * area, 0.0);
    outAlbedo = vec4(diffuse, 0.0);
}
