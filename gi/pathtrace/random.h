// Per-sample random numbers for the path tracer. Every (seed, pixel, sample) triple starts its
// own PCG32 stream, so an image depends on the seed and the sample count only, never on how
// the pixels were spread over threads.
#pragma once

#include <cstdint>

namespace voxgi::pt {

class Rng {
public:
    Rng(std::uint64_t seed, std::uint64_t pixel, std::uint64_t sample) {
        // Mixing the key through splitmix64 decorrelates neighbouring pixels and samples.
        std::uint64_t key = mix(seed ^ mix(pixel * 0x9E3779B97F4A7C15ull + mix(sample + 0x632BE59BD9B4E019ull)));
        increment_ = (mix(key ^ 0xD1B54A32D192ED03ull) << 1u) | 1u;
        state_ = 0;
        next();
        state_ += key;
        next();
    }

    std::uint32_t next() {
        std::uint64_t old = state_;
        state_ = old * 6364136223846793005ull + increment_;
        auto xorshifted = std::uint32_t(((old >> 18u) ^ old) >> 27u);
        auto rot = std::uint32_t(old >> 59u);
        return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
    }

    // Uniform in [0, 1): 24 random bits keep the value strictly below one in float.
    float uniform() { return float(next() >> 8) * (1.0f / 16777216.0f); }

private:
    static std::uint64_t mix(std::uint64_t z) {
        z += 0x9E3779B97F4A7C15ull;
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    std::uint64_t state_ = 0;
    std::uint64_t increment_ = 1;
};

}  // namespace voxgi::pt
