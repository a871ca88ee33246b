#version 450 core
// The viewer's picture: the accumulated HDR frame (or one AOV) through the display transform the
// PNG writer uses (shaders/shared/tone_map.h), so what is on screen is what a screenshot's PNG
// holds. The default framebuffer is not sRGB: the curve is applied here.
in vec2 vUv;
out vec4 outColor;

layout(binding = 0) uniform sampler2D uDirect;    // sum over uFrames
layout(binding = 1) uniform sampler2D uIndirect;  // sum over uFrames
layout(binding = 2) uniform sampler2D uAlbedo;
layout(binding = 3) uniform sampler2D uNormal;
uniform float uInvFrames;
uniform float uExposureScale;  // 2^stops
uniform int uMode;             // 0 beauty, 1 direct, 2 indirect, 3 albedo, 4 normal

#include "view/tone_map.glsl"

void main() {
    vec3 direct = texture(uDirect, vUv).rgb * uInvFrames;
    vec3 indirect = texture(uIndirect, vUv).rgb * uInvFrames;
    vec3 c;
    if (uMode == 0) c = toDisplay(uExposureScale * (direct + indirect));
    else if (uMode == 1) c = toDisplay(uExposureScale * direct);
    else if (uMode == 2) c = toDisplay(uExposureScale * indirect);
    else if (uMode == 3) c = texture(uAlbedo, vUv).rgb;  // reflectance: shown as stored
    else c = texture(uNormal, vUv).xyz * 0.5 + 0.5;
    outColor = vec4(c, 1.0);
}
