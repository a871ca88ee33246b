#include "tools/embree_share.h"

#include <tbb/parallel_for.h>

#include "gi/pathtrace/path_tracer.h"
#include "volumes/openvdb_reference.h"

namespace voxgi::cli {

EmbreeShare measureEmbreeShare(PathTracer& tracer, int spp) {
    const int first = tracer.samplesPerPixel();
    const std::uint64_t raysBefore = tracer.raysTraced();
    double start = processCpuSeconds();
    tracer.render(spp);
    const double pathCpu = processCpuSeconds() - start;
    const double rays = double(tracer.raysTraced() - raysBefore);
    tracer.rayTracer().startLog();
    // Sample index outermost: samplePixel() keeps only the last few indices' light subpaths.
    for (int s = first; s < first + spp; ++s)
        tbb::parallel_for(0, tracer.height(), [&](int y) {
            for (int x = 0; x < tracer.width(); ++x) tracer.samplePixel(x, y, std::uint64_t(s));
        });
    const std::vector<LoggedRay> logged = tracer.rayTracer().stopLog();
    start = processCpuSeconds();
    tracer.rayTracer().replayBare(logged);
    const double bareCpu = processCpuSeconds() - start;
    EmbreeShare share;
    share.rays = double(logged.size());
    share.pathPerCpuS = rays / pathCpu;
    share.barePerCpuS = double(logged.size()) / bareCpu;
    return share;
}

}  // namespace voxgi::cli
