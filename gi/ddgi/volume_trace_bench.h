// `voxgi bench ddgi`'s GL section on probe rays cast through the NanoVDB geometry volume
// (VolumeTracerGl) at several voxel sizes and through the triangles' BVH: memory, GPU time and
// rays per second; then whole updates with ddgi.trace = volume and bvh (rays traced, shaded
// and blended on the GPU).
#pragma once

#include <glm/glm.hpp>

#include "gi/ddgi/ddgi_desc.h"

namespace voxgi {

class DdgiSystem;
class RayTracer;

// Every probe's rays of the system's last frame, through volumes with 4, 8 and 16 voxels per
// smallest probe spacing and through the triangles. Needs a current GL context.
void printVolumeTraceBench(const DdgiSystem& ddgi);

// Updates of a field with `desc` and trace = volume at trace_voxels 4, 8 and 16 (and 16
// without classification), then trace = bvh at 8, from `eye`:
// median wall time of the update and its stages, the GPU time of the trace + shade kernel and
// of the blend kernels, over `frames` frames after two untimed ones.
void printVolumeUpdateBench(const RayTracer& tracer, DdgiDesc desc, glm::vec3 eye, int frames);

}  // namespace voxgi
