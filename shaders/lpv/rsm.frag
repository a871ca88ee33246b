#version 450 core
// One reflective-shadow-map texel: the surfel's position and area, normal, the diffuse flux it
// reflects (W) and its diffuse albedo. Units as in direct_light.frag.
#include "common/scene_data.glsl"

in vec3 vPosition;
in vec3 vNormal;
in vec2 vUv;

uniform int uKind;               // 0 perspective (point, spot, quad hemicube), 2 orthographic (sun)
uniform vec3 uLightPosition;
uniform vec3 uLightForward;      // the face's viewing axis
uniform vec3 uLightDirection;    // spot axis / sun direction (the way light travels)
uniform vec3 uLightColor;        // W/sr (point, spot; quad: L * A) or W/m^2 (sun)
uniform vec3 uEmitterNormal;     // quad: cosine emission about this normal
uniform vec2 uSpotCos;
uniform float uTexelSolidAngle;  // perspective: texel solid angle on the unit image plane
uniform float uOrthoTexelArea;   // orthographic: texel area in m^2
uniform sampler2DArray uTextures;

layout(location = 0) out vec4 outPosition;  // xyz, w = surfel area (m^2)
layout(location = 1) out vec4 outNormal;    // xyz, w = 1 where a surface was hit
layout(location = 2) out vec4 outFlux;      // rgb reflected diffuse flux (W)
layout(location = 3) out vec4 outAlbedo;    // rgb diffuse albedo

void main() {
    MaterialGpu m = materials[triangleMaterial[gl_PrimitiveID]];
    vec3 geometric = normalize(cross(dFdx(vPosition), dFdy(vPosition)));
    vec3 n = length(vNormal) > 0.0 ? normalize(vNormal) : geometric;
    vec3 toLight = uKind == 2 ? -uLightDirection : normalize(uLightPosition - vPosition);
    if (dot(geometric, toLight) < 0.0) geometric = -geometric;
    if (dot(n, geometric) < 0.0) n = -n;  // two-sided, like the frame renderer
    vec3 albedo = m.albedo.rgb;
    if (m.textureLayer >= 0) albedo *= texture(uTextures, vec3(vUv.x, 1.0 - vUv.y, float(m.textureLayer))).rgb;
    vec3 diffuse = diffuseAlbedo(albedo, m.metallic, m.specular);
    float cosSurface = max(dot(n, toLight), 0.0);

    vec3 incidentFlux;  // W arriving on the surfel
    float area;
    if (uKind == 2) {
        incidentFlux = uLightColor * uOrthoTexelArea;  // E cos * (texel area / cos)
        area = uOrthoTexelArea / max(cosSurface, 0.05);
    } else {
        vec3 d = vPosition - uLightPosition;
        float dist = length(d);
        vec3 w = d / dist;
        float c = max(dot(w, uLightForward), 1e-4);
        float solidAngle = uTexelSolidAngle * c * c * c;
        vec3 intensity = uLightColor;
        if (uSpotCos.x > -1.5) intensity *= smoothstep(uSpotCos.x, uSpotCos.y, dot(w, uLightDirection));
        if (dot(uEmitterNormal, uEmitterNormal) > 0.0) intensity *= max(dot(uEmitterNormal, w), 0.0);
        incidentFlux = intensity * solidAngle;
        area = solidAngle * dist * dist / max(cosSurface, 0.05);
    }
    if (cosSurface <= 0.0) incidentFlux = vec3(0.0);
    outPosition = vec4(vPosition, area);
    outNormal = vec4(n, 1.0);
    outFlux = vec4(diffuse * incidentFlux, 0.0);
    outAlbedo = vec4(diffuse, 0.0);
}
