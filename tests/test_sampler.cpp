// The path tracer's sample points: Sobol's first two dimensions form a (0, 2)-sequence in base
// 2 (every 2^m consecutive aligned points put one point in each elementary interval of area
// 2^-m), every dimension is stratified in 1D, and Owen scrambling and the per-decision index
// shuffle keep both properties for every pixel and decision while making decisions differ.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <vector>

#include "gi/pathtrace/sampler.h"
#include "gi/sampling/sobol.h"

using namespace voxgi;

namespace {

// True when the points form a (0, m, 2)-net: each of the 2^m boxes of every shape
// 2^-i x 2^-(m-i) holds exactly one point.
bool isZeroNet(const std::vector<glm::dvec2>& points, int m) {
    for (int i = 0; i <= m; ++i) {
        const int nx = 1 << i, ny = 1 << (m - i);
        std::vector<int> count(std::size_t(nx) * std::size_t(ny), 0);
        for (const glm::dvec2& p : points) {
            const int x = std::min(int(p.x * nx), nx - 1), y = std::min(int(p.y * ny), ny - 1);
            if (++count[std::size_t(y) * std::size_t(nx) + std::size_t(x)] > 1) return false;
        }
    }
    return true;
}

bool isStratified(const std::vector<double>& values) {
    std::set<int> strata;
    for (double v : values) strata.insert(int(v * double(values.size())));
    return strata.size() == values.size();
}

double unit(std::uint32_t x) { return double(x) / 4294967296.0; }

}  // namespace

TEST(Sobol, KnownFirstPoints) {
    // Indexed by the binary digits of the index (not Gray code): dimension 0 is the van der
    // Corput sequence; dimension 1 (x + 1) has direction numbers 1/2, 3/4, 5/8.
    const double d0[] = {0.0, 0.5, 0.25, 0.75, 0.125};
    const double d1[] = {0.0, 0.5, 0.75, 0.25, 0.625};
    for (std::uint32_t i = 0; i < 5; ++i) {
        EXPECT_DOUBLE_EQ(unit(sobol(i, 0)), d0[i]) << i;
        EXPECT_DOUBLE_EQ(unit(sobol(i, 1)), d1[i]) << i;
    }
}

TEST(Sobol, FirstTwoDimensionsAreAZeroTwoSequence) {
    for (int m = 1; m <= 10; ++m)
        for (std::uint32_t block : {0u, 1u, 7u}) {  // aligned blocks anywhere in the sequence
            std::vector<glm::dvec2> points;
            for (std::uint32_t i = 0; i < (1u << m); ++i) {
                const std::uint32_t index = (block << m) + i;
                points.push_back({unit(sobol(index, 0)), unit(sobol(index, 1))});
            }
            EXPECT_TRUE(isZeroNet(points, m)) << "m " << m << " block " << block;
        }
}

TEST(Sobol, EveryDimensionIsStratifiedAndScramblingKeepsIt) {
    for (int d = 0; d < kSobolDimensions; ++d)
        for (int m : {4, 8, 12}) {
            std::vector<double> plain, scrambled;
            for (std::uint32_t i = 0; i < (1u << m); ++i) {
                plain.push_back(unit(sobol(i, d)));
                scrambled.push_back(unit(nestedUniformScramble(sobol(i, d), 0x1234567u + std::uint32_t(d))));
            }
            EXPECT_TRUE(isStratified(plain)) << "dimension " << d << " m " << m;
            EXPECT_TRUE(isStratified(scrambled)) << "dimension " << d << " m " << m;
        }
}

TEST(Sobol, NestedUniformScrambleIsABijectionThatKeepsStrata) {
    // 2^16 inputs that share their low 16 bits map to distinct outputs, and inputs that share
    // their top k bits share their outputs' top k bits.
    std::set<std::uint32_t> seen;
    for (std::uint32_t i = 0; i < (1u << 16); ++i) seen.insert(nestedUniformScramble(i << 16, 99u));
    EXPECT_EQ(seen.size(), std::size_t(1) << 16);
    for (std::uint32_t x : {0x12345678u, 0xDEADBEEFu, 0x80000001u})
        for (std::uint32_t low : {0u, 1u, 0xFFFFu})
            EXPECT_EQ(nestedUniformScramble(x, 7u) >> 16, nestedUniformScramble((x & 0xFFFF0000u) | low, 7u) >> 16);
}

TEST(PathSampler, EachDecisionIsANetPerPixelAndDecisionsDiffer) {
    for (std::uint64_t pixel : {0ull, 12345ull})
        for (std::uint32_t decision : {0u, 1u, 5u, 40u}) {
            for (int m : {2, 6, 10}) {
                std::vector<glm::dvec2> points;
                std::vector<double> third;
                for (std::uint64_t s = 0; s < (1ull << m); ++s) {
                    const pt::PathSampler sampler(3, pixel, s);
                    const glm::vec3 p = sampler.get3D(decision);
                    points.push_back(glm::dvec2(p.x, p.y));
                    third.push_back(p.z);
                    EXPECT_TRUE(p.x >= 0.0f && p.x < 1.0f && p.y >= 0.0f && p.y < 1.0f && p.z >= 0.0f && p.z < 1.0f);
                }
                EXPECT_TRUE(isZeroNet(points, m)) << "pixel " << pixel << " decision " << decision << " m " << m;
                EXPECT_TRUE(isStratified(third)) << "pixel " << pixel << " decision " << decision << " m " << m;
            }
        }
    // Two decisions of one path, and one decision of two pixels, are not the same points:
    // the correlation of their first coordinates over 4096 samples is near zero.
    auto correlation = [](auto a, auto b) {
        double sa = 0, sb = 0, sab = 0, saa = 0, sbb = 0;
        const int n = 4096;
        for (int s = 0; s < n; ++s) {
            double x = a(s), y = b(s);
            sa += x, sb += y, sab += x * y, saa += x * x, sbb += y * y;
        }
        double cov = sab / n - sa / n * sb / n;
        return cov / std::sqrt((saa / n - sa * sa / n / n) * (sbb / n - sb * sb / n / n));
    };
    EXPECT_LT(std::abs(correlation([](int s) { return pt::PathSampler(3, 7, std::uint64_t(s)).get2D(1).x; },
                                   [](int s) { return pt::PathSampler(3, 7, std::uint64_t(s)).get2D(2).x; })),
              0.05);
    EXPECT_LT(std::abs(correlation([](int s) { return pt::PathSampler(3, 7, std::uint64_t(s)).get2D(1).x; },
                                   [](int s) { return pt::PathSampler(3, 8, std::uint64_t(s)).get2D(1).x; })),
              0.05);
}
