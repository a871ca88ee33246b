#version 450 core
// Adds what the eye sees directly: emitters' radiance and, where no surface is hit, the sky
// along the pixel's ray (the frame's jittered view-projection, inverted).
#define SCREEN_PASS_ADDITIVE
#include "common/screen_pass.glsl"
#include "common/sky.glsl"

uniform sampler2D uPosition;
uniform sampler2D uEmission;
uniform mat4 uInverseViewProjection;
uniform vec3 uEye;
uniform vec2 uViewport;

void main() {
    ivec2 pixel;
    if (!screenPixel(pixel)) return;
    if (texelFetch(uPosition, pixel, 0).w > 0.0) {
        addToTarget(pixel, vec4(texelFetch(uEmission, pixel, 0).rgb, 1.0));
        return;
    }
    vec4 far = uInverseViewProjection * vec4(2.0 * (vec2(pixel) + 0.5) / uViewport - 1.0, 1.0, 1.0);
    addToTarget(pixel, vec4(skyRadiance(normalize(far.xyz / far.w - uEye)), 1.0));
}
