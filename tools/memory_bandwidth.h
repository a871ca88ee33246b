// This machine's memory bandwidth as STREAM's triad measures it (a[i] = b[i] + s c[i] over
// arrays far larger than the caches), the denominator of every bandwidth ratio the benchmarks
// print (`voxgi bench limits`, `voxgi bench propagation`).
#pragma once

namespace voxgi::cli {

// GB/s (1e9 bytes) of the triad on `threads` threads (0: all), counting 24 bytes per element
// as STREAM does (two doubles read, one written; the write-allocate read is not counted). The
// best of `repeats` passes over 3 arrays of `megabytes` MB each.
double streamTriadGBs(int threads, int repeats = 5, int megabytes = 128);

}  // namespace voxgi::cli
