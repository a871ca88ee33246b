// Shared by the DDGI update kernels; layouts match gi/ddgi/probe_blend.h.
#ifndef VOXGI_DDGI_BLEND_COMMON_GLSL
#define VOXGI_DDGI_BLEND_COMMON_GLSL
struct BlendJob {
    int probe;
    int irradianceX;
    int irradianceY;
    int distanceX;
    int distanceY;
    int rayBase;
    float hysteresis;
    float maxDistance;
};
layout(std430, binding = 0) readonly buffer Jobs { BlendJob jobs[]; };
#endif
