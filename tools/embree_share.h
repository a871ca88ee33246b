// The path tracer's rays per CPU second against Embree's alone on the very same rays: the
// denominator of every path-tracer throughput ratio (`voxgi bench pathtrace`, `voxgi bench limits`).
#pragma once

namespace voxgi {
class PathTracer;
}

namespace voxgi::cli {

struct EmbreeShare {
    double rays = 0.0;        // rays traced (and replayed)
    double pathPerCpuS = 0.0; // the path tracer's rays per CPU second (all threads), shading included
    double barePerCpuS = 0.0; // rtcIntersect1 / rtcOccluded1 alone on the same rays
};

// Renders `spp` more samples per pixel (timed), traces them again with the ray log on (samples
// are deterministic: the same paths) and replays the logged rays through Embree alone.
EmbreeShare measureEmbreeShare(PathTracer& tracer, int spp);

}  // namespace voxgi::cli
