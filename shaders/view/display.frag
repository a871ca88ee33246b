#version 450 core
// The viewer's picture: the accumulated HDR frame (or one AOV) tone-mapped with the same ACES
// fit and sRGB curve as the PNG writer (scenes/image.cpp toneMapToSrgb), so what is on screen is
// what a screenshot's PNG holds. The default framebuffer is not sRGB: the curve is applied here.
in vec2 vUv;
out vec4 outColor;

layout(binding = 0) uniform sampler2D uDirect;    // sum over uFrames
layout(binding = 1) uniform sampler2D uIndirect;  // sum over uFrames
layout(binding = 2) uniform sampler2D uAlbedo;
layout(binding = 3) uniform sampler2D uNormal;
uniform float uInvFrames;
uniform float uExposureScale;  // 2^stops
uniform int uMode;             // 0 beauty, 1 direct, 2 indirect, 3 albedo, 4 normal

vec3 acesSrgb(vec3 x) {
    x = max(x, vec3(0.0)) * uExposureScale;
    x = clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
    return mix(1.055 * pow(x, vec3(1.0 / 2.4)) - 0.055, 12.92 * x, lessThanEqual(x, vec3(0.0031308)));
}

void main() {
    vec3 direct = texture(uDirect, vUv).rgb * uInvFrames;
    vec3 indirect = texture(uIndirect, vUv).rgb * uInvFrames;
    vec3 c;
    if (uMode == 0) c = acesSrgb(direct + indirect);
    else if (uMode == 1) c = acesSrgb(direct);
    else if (uMode == 2) c = acesSrgb(indirect);
    else if (uMode == 3) c = texture(uAlbedo, vUv).rgb;  // reflectance: shown as stored
    else c = texture(uNormal, vUv).xyz * 0.5 + 0.5;
    outColor = vec4(c, 1.0);
}
