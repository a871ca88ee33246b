// Light that has decayed below FLT_MIN (1.2e-38) is treated as zero while an object of this
// type lives: on x86, arithmetic on subnormal floats takes ~100 times as long. A long SH
// propagation whose light had died away (lpv.steps in the thousands) spent almost all its time
// there (4000 steps: 1.8 s, 8000: 34 s), and so did the ordinates' sweeps far from the sources.
// The thread's floating-point mode is restored afterwards.
#pragma once

#if defined(__SSE__)
#include <xmmintrin.h>
#endif

namespace voxgi::detail {

class SubnormalsFlushed {
public:
#if defined(__SSE__)
    SubnormalsFlushed() : saved_(_mm_getcsr()) { _mm_setcsr(saved_ | kFlushToZero | kDenormalsAreZero); }
    ~SubnormalsFlushed() { _mm_setcsr(saved_); }
    SubnormalsFlushed(const SubnormalsFlushed&) = delete;
    SubnormalsFlushed& operator=(const SubnormalsFlushed&) = delete;

private:
    static constexpr unsigned kFlushToZero = 0x8000, kDenormalsAreZero = 0x0040;
    unsigned saved_;
#endif
};

}  // namespace voxgi::detail
