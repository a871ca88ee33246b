// Integer hashes with full avalanche, for keying scrambles, hash tables and random streams.
#pragma once

#include <cstdint>

namespace voxgi {

// splitmix64's finalizer (Stafford's mix 13 constants).
inline std::uint64_t mix64(std::uint64_t x) {
    x ^= x >> 30;
    x *= 0xBF58476D1CE4E5B9ull;
    x ^= x >> 27;
    x *= 0x94D049BB133111EBull;
    return x ^ (x >> 31);
}

// Wellons' lowbias32.
inline std::uint32_t hash32(std::uint32_t x) {
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

}  // namespace voxgi
