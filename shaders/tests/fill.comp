#version 450 core
// Test kernel: out[i] = FILL_SCALE * i * kPi, with kPi from an included file.
#include "shared/constants.h"
layout(local_size_x = 64) in;
layout(std430, binding = 0) buffer Out { float values[]; };
void main() { values[gl_LocalInvocationIndex] = FILL_SCALE * float(gl_LocalInvocationIndex) * kPi; }
