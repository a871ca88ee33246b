// `voxgi bench ddgi`: probe-ray throughput against Embree alone on the same rays, the shading
// modes side by side, per-stage medians with and without probe culling, and the GL stages.
#pragma once

#include "gi/method.h"

namespace voxgi {

// Defaults: 16x8x12 probes and 256 rays unless the scene or --set gives them, 12 warm-up and
// 5 timed frames.
void runDdgiBench(const BenchRequest& request);

}  // namespace voxgi
