// Shared constants; the C++ side has the same values in gi/sampling and render/frame.
#ifndef VOXGI_CONSTANTS_GLSL
#define VOXGI_CONSTANTS_GLSL
const float PI = 3.14159265358979323846;
const float INV_PI = 0.31830988618379067154;
#endif
