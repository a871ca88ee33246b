#include "gi/sampling/sobol.h"

#include <array>

namespace voxgi {

namespace {

using Directions = std::array<std::array<std::uint32_t, 32>, kSobolDimensions>;

// Direction numbers v_k = m_k / 2^k (as 32-bit fixed point) from each dimension's primitive
// polynomial of degree s with inner coefficients a_1..a_{s-1} (a_1 the top bit of `inner`) by
// Bratley and Fox's recurrence m_k = 2 a_1 m_{k-1} ^ ... ^ 2^{s-1} a_{s-1} m_{k-s+1} ^
// 2^s m_{k-s} ^ m_{k-s}. Dimension 0 is van der Corput's.
Directions makeDirections() {
    struct Polynomial {
        int degree;
        std::uint32_t inner;
        std::uint32_t initial[3];
    };
    // Joe and Kuo's table, dimensions 2 to 4: x + 1; x^2 + x + 1; x^3 + x + 1.
    constexpr Polynomial kPolynomials[kSobolDimensions - 1] = {{1, 0, {1, 0, 0}}, {2, 1, {1, 3, 0}}, {3, 1, {1, 3, 1}}};
    Directions v{};
    for (int k = 0; k < 32; ++k) v[0][std::size_t(k)] = 1u << (31 - k);
    for (int d = 1; d < kSobolDimensions; ++d) {
        const Polynomial& p = kPolynomials[d - 1];
        std::uint32_t m[32];
        for (int k = 0; k < 32; ++k) {
            if (k < p.degree) {
                m[k] = p.initial[k];
                continue;
            }
            std::uint32_t value = m[k - p.degree] ^ (m[k - p.degree] << p.degree);
            for (int i = 1; i < p.degree; ++i)
                if ((p.inner >> (p.degree - 1 - i)) & 1u) value ^= m[k - i] << i;
            m[k] = value;
        }
        for (int k = 0; k < 32; ++k) v[std::size_t(d)][std::size_t(k)] = m[k] << (31 - k);
    }
    return v;
}

const Directions kDirections = makeDirections();

}  // namespace

namespace {
SobolReversedTables makeReversedTables() {
    SobolReversedTables r{};
    for (int d = 0; d < kSobolDimensions; ++d)
        for (int byte = 0; byte < 4; ++byte)
            for (std::uint32_t value = 0; value < 256; ++value) {
                std::uint32_t x = 0;
                for (int bit = 0; bit < 8; ++bit)
                    if ((value >> bit) & 1u) x ^= kDirections[std::size_t(d)][std::size_t(31 - (8 * byte + bit))];
                r.t[d][byte][value] = reverseBits(x);
            }
    return r;
}
}  // namespace

// Built after kDirections (above, in this translation unit); readers run after static
// initialisation.
const SobolReversedTables kSobolReversedTables = makeReversedTables();

std::uint32_t sobol(std::uint32_t index, int dimension) { return reverseBits(sobolReversed(reverseBits(index), dimension)); }

std::uint32_t nestedUniformScramble(std::uint32_t x, std::uint32_t seed) {
    return reverseBits(owenPermutationReversed(reverseBits(x), seed));
}

}  // namespace voxgi
