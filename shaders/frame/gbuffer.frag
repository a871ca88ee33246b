#version 450 core
// Writes the G-buffer (encoding in shaders/shared/gbuffer.h): world position, camera-facing
// shading normal + roughness, albedo + metallic, emission (front faces only) + specular.
#include "common/scene_data.glsl"
#include "shared/gbuffer.h"

in vec3 vPosition;
in vec3 vNormal;
in vec2 vUv;

uniform vec3 uEye;
uniform sampler2DArray uTextures;

layout(location = 0) out vec4 outPosition;
layout(location = 1) out vec4 outNormal;
layout(location = 2) out vec4 outAlbedo;
layout(location = 3) out vec4 outEmission;

void main() {
    MaterialGpu m = materials[triangleMaterial[gl_PrimitiveID]];
    vec3 geometric = normalize(cross(dFdx(vPosition), dFdy(vPosition)));
    vec3 n = length(vNormal) > 0.0 ? normalize(vNormal) : geometric;
    vec3 toEye = uEye - vPosition;
    if (dot(geometric, toEye) < 0.0) geometric = -geometric;
    // Two-sided shading: the normal faces the side the camera sees.
    if (dot(n, geometric) < 0.0) n = -n;
    vec3 albedo = m.albedo.rgb;
    if (m.textureLayer >= 0) albedo *= texture(uTextures, vec3(vUv.x, 1.0 - vUv.y, float(m.textureLayer))).rgb;
    GBufferSurface s;
    s.position = vPosition;
    s.normal = n;
    s.albedo = albedo;
    s.emission = gl_FrontFacing ? m.emission.rgb : vec3(0.0);
    s.roughness = m.roughness;
    s.metallic = m.metallic;
    s.specular = m.specular;
    s.transmission = m.albedo.a;
    GBufferTexels t = encodeGBuffer(s);
    outPosition = t.position;
    outNormal = t.normal;
    outAlbedo = t.albedo;
    outEmission = t.emission;
}
