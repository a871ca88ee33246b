#version 450 core
// One reflective-shadow-map texel: the surfel's position and area, normal, the diffuse flux it
// reflects (W) and its diffuse albedo. The light is lights[uLight], evaluated by the shared
// light model (shaders/shared/light_model.h).
#include "common/scene_data.glsl"

in vec3 vPosition;
in vec3 vNormal;
in vec2 vUv;

uniform int uLight;
uniform vec2 uQuadSample;        // quad lights: the point of the quad the map is rendered from
uniform vec3 uFaceOrigin;        // perspective faces: the eye of the face
uniform vec3 uFaceForward;       // the face's viewing axis
uniform float uTexelSolidAngle;  // perspective: texel solid angle on the unit image plane
uniform float uOrthoTexelArea;   // orthographic (sun): texel area in m^2
uniform sampler2DArray uTextures;

layout(location = 0) out vec4 outPosition;  // xyz, w = surfel area (m^2)
layout(location = 1) out vec4 outNormal;    // xyz, w = 1 where a surface was hit
layout(location = 2) out vec4 outFlux;      // rgb reflected diffuse flux (W)
layout(location = 3) out vec4 outAlbedo;    // rgb diffuse albedo

void main() {
    MaterialGpu m = materials[triangleMaterial[gl_PrimitiveID]];
    PackedLight light = lights[uLight];
    IncidentLight incident = evaluateLight(light, vPosition, uQuadSample);
    vec3 toLight = incident.direction;
    vec3 geometric = normalize(cross(dFdx(vPosition), dFdy(vPosition)));
    vec3 n = length(vNormal) > 0.0 ? normalize(vNormal) : geometric;
    if (dot(geometric, toLight) < 0.0) geometric = -geometric;
    if (dot(n, geometric) < 0.0) n = -n;  // two-sided, like the frame renderer
    vec3 albedo = m.albedo.rgb;
    if (m.textureLayer >= 0) albedo *= texture(uTextures, vec3(vUv.x, 1.0 - vUv.y, float(m.textureLayer))).rgb;
    vec3 diffuse = diffuseAlbedo(albedo, m.metallic, m.specular, m.albedo.a);
    float cosSurface = max(dot(n, toLight), 0.0);

    vec3 incidentFlux;  // W arriving on the surfel
    float area;
    if (light.kind.x == kLightDirectional) {
        incidentFlux = incident.irradiance * uOrthoTexelArea;  // E cos * (texel area / cos)
        area = uOrthoTexelArea / max(cosSurface, 0.05);
    } else {
        // The texel's solid angle seen from the face's eye; the light's intensity toward the
        // surfel is its irradiance at normal incidence times the distance squared.
        vec3 d = vPosition - uFaceOrigin;
        float dist = length(d);
        float c = max(dot(d / dist, uFaceForward), 1e-4);
        float solidAngle = uTexelSolidAngle * c * c * c;
        incidentFlux = incident.irradiance * (incident.distance * incident.distance) * solidAngle;
        area = solidAngle * dist * dist / max(cosSurface, 0.05);
    }
    if (cosSurface <= 0.0) incidentFlux = vec3(0.0);
    outPosition = vec4(vPosition, area);
    outNormal = vec4(n, 1.0);
    outFlux = vec4(diffuse * incidentFlux, 0.0);
    outAlbedo = vec4(diffuse, 0.0);
}
