#version 450 core
// Ambient baseline: every visible surface receives the same irradiance E from all directions,
// so its indirect outgoing radiance is the diffuse albedo / pi times E (no occlusion, no
// colour bleeding: the floor a GI method has to beat).
#include "shared/constants.h"

uniform sampler2D uPosition;
uniform sampler2D uAlbedo;
uniform sampler2D uEmission;
uniform vec3 uIrradiance;

layout(location = 0) out vec4 outColor;

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    if (texelFetch(uPosition, pixel, 0).w == 0.0) { outColor = vec4(0.0); return; }
    vec4 am = texelFetch(uAlbedo, pixel, 0);
    float specular = texelFetch(uEmission, pixel, 0).w;
    vec3 diffuse = (1.0 - am.w) * (1.0 - specular) * am.rgb;
    outColor = vec4(diffuse * kInvPi * uIrradiance, 1.0);
}
