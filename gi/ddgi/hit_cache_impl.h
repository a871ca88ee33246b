// HitCache::group (a template: the per-hit accessor is inlined into the grouping loop).
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace voxgi {

template <typename HitFn>
void HitCache::group(float cellSize, std::size_t runs, std::size_t runLength, HitFn&& hit) {
    begin(cellSize, runs * runLength);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, runs, 4), [&](const tbb::blocked_range<std::size_t>& r) {
        Writer w(*this);
        for (std::size_t run = r.begin(); run != r.end(); ++run)
            for (std::size_t i = 0; i < runLength; ++i) {
                glm::vec3 p, n;
                if (hit(run, i, &p, &n)) w.add(run * runLength + i, p, n);
                else w.skip(run * runLength + i);
            }
    });
    finish();
}

}  // namespace voxgi
