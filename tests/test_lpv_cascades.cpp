// How clpv's cascades share the light (gi/lpv/cascades.h): every (source, point) pair the
// coarsest cascade holds is carried exactly once, by one cascade or split between neighbours
// in the border bands; near pairs by the finest cascade holding both, far light by coarser ones.
#include <gtest/gtest.h>

#include <random>

#include "gi/lpv/cascades.h"

using namespace voxgi;

namespace {

std::vector<CascadePlacement> threeCascades() {
    LpvDesc desc = lpvDefaults(true);
    Bounds b;
    b.min = glm::vec3(-3.0f, 0.0f, -2.0f);
    b.max = glm::vec3(4.0f, 2.5f, 3.0f);
    return placeCascades(desc, b, glm::vec3(0.3f, 1.1f, 2.0f), glm::vec3(0.2f, -0.1f, -1.0f));
}

// S_L(x): the share of x cascades 0..L hold.
float held(const std::vector<CascadePlacement>& cascades, std::size_t level, glm::vec3 x) {
    float outside = 1.0f;
    for (std::size_t j = 0; j <= level; ++j) outside *= 1.0f - cascadeInlier(cascades[j], x);
    return 1.0f - outside;
}

}  // namespace

TEST(LpvCascades, EverySourcePointPairIsCarriedOnce) {
    const auto cascades = threeCascades();
    ASSERT_EQ(cascades.size(), 3u);
    const CascadeGrid& outer = cascades.back().grid;
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    auto randomPoint = [&]() {
        // Mostly near the camera, where the cascades nest and their bands overlap.
        const glm::vec3 lo = outer.worldMin(), hi = outer.worldMax();
        const float spread = u(rng) < 0.5f ? 0.25f : 1.0f;
        const glm::vec3 c = 0.5f * (lo + hi);
        return c + (glm::vec3(u(rng), u(rng), u(rng)) - 0.5f) * (hi - lo) * spread;
    };
    int nearPairs = 0;
    for (int trial = 0; trial < 20000; ++trial) {
        const glm::vec3 s = randomPoint(), p = randomPoint();
        // What the apply pass reads of each cascade (apply.frag): S_L(p) x ring + (S_L - S_{L-1})(p) x inner.
        double carried = 0.0;
        float ringSum = 0.0f;
        for (std::size_t level = 0; level < cascades.size(); ++level) {
            const SourceShares share = sourceShares(cascades, level, s);
            ASSERT_GE(share.ring, 0.0f);
            ASSERT_GE(share.inner, 0.0f);
            if (level == 0) {
                EXPECT_EQ(share.inner, 0.0f);
            }
            ringSum += share.ring;
            const float sl = held(cascades, level, p), prev = level == 0 ? 0.0f : held(cascades, level - 1, p);
            carried += double(share.ring) * sl + double(share.inner) * (sl - prev);
        }
        // The VPL is split over the rings without loss...
        EXPECT_NEAR(ringSum, held(cascades, 2, s), 1e-5f);
        // ...and the pair is counted once wherever the outer cascade holds both ends.
        const double want = double(held(cascades, 2, s)) * double(held(cascades, 2, p));
        ASSERT_NEAR(carried, want, 1e-5) << "trial " << trial;
        // A pair well inside the finest cascade is carried by it alone.
        if (cascadeInlier(cascades[0], s) == 1.0f && cascadeInlier(cascades[0], p) == 1.0f) {
            ++nearPairs;
            EXPECT_EQ(sourceShares(cascades, 0, s).ring, 1.0f);
            EXPECT_EQ(sourceShares(cascades, 1, s).ring, 0.0f);
            EXPECT_EQ(sourceShares(cascades, 2, s).ring, 0.0f);
        }
    }
    EXPECT_GT(nearPairs, 100);
}

TEST(LpvCascades, OneVolumeTakesEveryVplWhole) {
    LpvDesc desc = lpvDefaults(false);
    Bounds b;
    b.min = glm::vec3(0.0f);
    b.max = glm::vec3(1.0f, 2.0f, 0.5f);
    const auto one = placeCascades(desc, b, glm::vec3(5.0f), glm::vec3(-1.0f));
    ASSERT_EQ(one.size(), 1u);
    for (glm::vec3 x : {glm::vec3(0.0f), glm::vec3(1.0f, 2.0f, 0.5f), glm::vec3(0.01f, 1.99f, 0.3f)}) {
        const SourceShares share = sourceShares(one, 0, x);
        EXPECT_EQ(share.ring, 1.0f);
        EXPECT_EQ(share.inner, 0.0f);
    }
}
