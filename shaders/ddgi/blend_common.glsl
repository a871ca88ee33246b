// Shared by the DDGI update kernels; layouts match gi/ddgi/probe_blend.h. Define
// DDGI_JOBS_ACCESS (empty) before including to write the jobs.
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
#ifndef DDGI_JOBS_ACCESS
#define DDGI_JOBS_ACCESS readonly
#endif
layout(std430, binding = 0) DDGI_JOBS_ACCESS buffer Jobs { BlendJob jobs[]; };
#endif
