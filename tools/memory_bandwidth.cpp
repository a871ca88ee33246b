#include "tools/memory_bandwidth.h"

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <memory>

#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>

namespace voxgi::cli {

double streamTriadGBs(int threads, int repeats, int megabytes) {
    const std::size_t n = std::size_t(megabytes) * 1000000 / sizeof(double);
    std::unique_ptr<double[]> a(new double[n]), b(new double[n]), c(new double[n]);
    tbb::task_arena arena(threads > 0 ? threads : tbb::info::default_concurrency());
    // The same static split for the first touch and the passes, so each thread streams the
    // pages it placed.
    const std::size_t grain = std::max<std::size_t>(1, n / std::size_t(64 * arena.max_concurrency()));
    auto forEach = [&](auto body) {
        arena.execute([&] {
            tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, grain), body, tbb::static_partitioner());
        });
    };
    forEach([&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t i = r.begin(); i < r.end(); ++i) {
            a[i] = 0.0;
            b[i] = 1.0;
            c[i] = 2.0;
        }
    });
    const double scalar = 3.0;
    double best = 1e30;
    for (int pass = 0; pass < repeats; ++pass) {
        const auto start = std::chrono::steady_clock::now();
        forEach([&](const tbb::blocked_range<std::size_t>& r) {
            double* __restrict out = a.get();
            const double* __restrict x = b.get();
            const double* __restrict y = c.get();
            for (std::size_t i = r.begin(); i < r.end(); ++i) out[i] = x[i] + scalar * y[i];
        });
        best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
    // Read one result so the passes cannot be dropped.
    volatile double sink = a[n / 2];
    (void)sink;
    return 24.0 * double(n) / best * 1e-9;
}

}  // namespace voxgi::cli
