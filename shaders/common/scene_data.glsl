// Scene buffers shared by the frame passes, bound by gl/scene_gpu.cpp; the layouts are the
// shared headers'.
#ifndef VOXGI_SCENE_DATA_GLSL
#define VOXGI_SCENE_DATA_GLSL
#include "shared/light_model.h"
#include "shared/material.h"
layout(std430, binding = 0) readonly buffer Materials { MaterialGpu materials[]; };
layout(std430, binding = 1) readonly buffer TriangleMaterials { uint triangleMaterial[]; };
layout(std430, binding = 2) readonly buffer Lights { PackedLight lights[]; };  // SceneGpu::bindLights
#endif
