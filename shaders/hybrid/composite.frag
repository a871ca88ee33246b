#version 450 core
// Adds what a layer of surfaces seen through mirrors and glass brings to each pixel: the light
// the frame's passes gave the layer times the pixel's weight (Fresnel and tint along the way),
// or, without a weight, radiance the rays collected themselves (emitters and sky).
uniform sampler2D uRadiance;
uniform sampler2D uWeight;
uniform int uWeighted;

layout(location = 0) out vec4 outColor;

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    vec3 radiance = texelFetch(uRadiance, pixel, 0).rgb;
    if (uWeighted != 0) radiance *= texelFetch(uWeight, pixel, 0).rgb;
    outColor = vec4(radiance, 1.0);
}
