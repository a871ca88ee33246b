#version 450 core
// Adds what the eye sees directly: emitters' radiance and, where no surface is hit, the sky
// along the pixel's ray (the frame's jittered view-projection, inverted).
#include "common/sky.glsl"

uniform sampler2D uPosition;
uniform sampler2D uEmission;
uniform mat4 uInverseViewProjection;
uniform vec3 uEye;
uniform vec2 uViewport;
layout(location = 0) out vec4 outColor;
void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    if (texelFetch(uPosition, pixel, 0).w > 0.0) {
        outColor = vec4(texelFetch(uEmission, pixel, 0).rgb, 1.0);
        return;
    }
    vec4 far = uInverseViewProjection * vec4(2.0 * gl_FragCoord.xy / uViewport - 1.0, 1.0, 1.0);
    outColor = vec4(skyRadiance(normalize(far.xyz / far.w - uEye)), 1.0);
}
