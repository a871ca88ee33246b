#version 450 core
// Adds what the eye sees directly: emitters' radiance and, where no surface is hit, the sky.
uniform sampler2D uPosition;
uniform sampler2D uEmission;
uniform vec3 uSky;
layout(location = 0) out vec4 outColor;
void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    bool hit = texelFetch(uPosition, pixel, 0).w > 0.0;
    outColor = vec4(hit ? texelFetch(uEmission, pixel, 0).rgb : uSky, 1.0);
}
