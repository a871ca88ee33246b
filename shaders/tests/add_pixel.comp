#version 450 core
// Test pass: adds (x, y, 1, 2) of each pixel to the bound target (gl::addToBoundTarget).
#define SCREEN_PASS_ADDITIVE
#include "common/screen_pass.glsl"

void main() {
    ivec2 pixel;
    if (!screenPixel(pixel)) return;
    addToTarget(pixel, vec4(vec2(pixel), 1.0, 2.0));
}
