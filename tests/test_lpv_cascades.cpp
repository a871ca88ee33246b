// How clpv's cascades share the light (gi/lpv/cascades.h): every (source, point) pair the
// coarsest cascade holds is carried exactly once, by one cascade or split between neighbours
// in the border bands; near pairs by the finest cascade holding both, far light by coarser ones.
#include <gtest/gtest.h>

#include <random>

#include "gi/lpv/cascades.h"

using namespace voxgi;

namespace {

Bounds roomBounds() {
    Bounds b;
    b.min = glm::vec3(-3.0f, 0.0f, -2.0f);
    b.max = glm::vec3(4.0f, 2.5f, 3.0f);
    return b;
}

std::vector<CascadePlacement> threeCascades(CascadeBounds bounds = CascadeBounds::Camera) {
    LpvDesc desc = lpvDefaults(true);
    desc.cascadeBounds = bounds;
    return placeCascades(desc, roomBounds(), glm::vec3(0.3f, 1.1f, 2.0f), glm::vec3(0.2f, -0.1f, -1.0f));
}

// S_L(x): the share of x cascades 0..L hold.
float held(const std::vector<CascadePlacement>& cascades, std::size_t level, glm::vec3 x) {
    float outside = 1.0f;
    for (std::size_t j = 0; j <= level; ++j) outside *= 1.0f - cascadeInlier(cascades[j], x);
    return 1.0f - outside;
}

}  // namespace

TEST(LpvCascades, EverySourcePointPairIsCarriedOnce) {
  for (CascadeBounds bounds : {CascadeBounds::Camera, CascadeBounds::Scene}) {
    SCOPED_TRACE(bounds == CascadeBounds::Camera ? "camera" : "scene");
    const auto cascades = threeCascades(bounds);
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
}

// lpv.cascade_bounds=scene: the coarsest cascade is the scene plus a cell and does not fade; the
// finer ones keep doubling their cells and stay inside the scene's bounds (a cell to spare), so
// a camera outside the scene still gets its finest cells on the scene's near side.
TEST(LpvCascades, SceneBoundsKeepEveryCascadeOnTheScene) {
    const Bounds b = roomBounds();
    LpvDesc desc = lpvDefaults(true);
    desc.cascadeBounds = CascadeBounds::Scene;
    for (glm::vec3 eye : {glm::vec3(0.3f, 1.1f, 2.0f), glm::vec3(0.5f, 1.0f, 30.0f)}) {
        const auto cascades = placeCascades(desc, b, eye, b.center() - eye);
        ASSERT_EQ(cascades.size(), 3u);
        const CascadePlacement& coarsest = cascades.back();
        EXPECT_TRUE(glm::all(glm::lessThanEqual(coarsest.grid.worldMin(), b.min)));
        EXPECT_TRUE(glm::all(glm::greaterThanEqual(coarsest.grid.worldMax(), b.max)));
        EXPECT_EQ(coarsest.fadeWidth, 0.0f);
        EXPECT_NEAR(coarsest.grid.cellSize * float(desc.resolution - 2), 7.0f, 1e-4f);  // the longest side
        for (std::size_t c = 0; c + 1 < cascades.size(); ++c) {
            const CascadeGrid& g = cascades[c].grid;
            EXPECT_NEAR(cascades[c + 1].grid.cellSize, 2.0f * g.cellSize, 1e-6f);
            EXPECT_GT(cascades[c].fadeWidth, 0.0f);
            for (int a = 0; a < 3; ++a) {
                if (float(desc.resolution - 2) * g.cellSize >= b.extent()[a]) {
                    // Wider than the scene along a: centred on it (within the snap to whole cells).
                    EXPECT_NEAR(0.5f * (g.worldMin()[a] + g.worldMax()[a]), b.center()[a], 0.5f * g.cellSize) << c;
                    continue;
                }
                // Otherwise within the bounds plus one cell and the snap.
                EXPECT_GE(g.worldMin()[a], b.min[a] - 1.5f * g.cellSize) << c << " " << a;
                EXPECT_LE(g.worldMax()[a], b.max[a] + 1.5f * g.cellSize) << c << " " << a;
            }
        }
    }
    // The camera placement of the same camera far outside: its finest cascade holds none of the scene.
    desc.cascadeBounds = CascadeBounds::Camera;
    const glm::vec3 far(0.5f, 1.0f, 30.0f);
    const CascadeGrid fine = placeCascades(desc, b, far, b.center() - far).front().grid;
    EXPECT_GT(fine.worldMin().z, b.max.z);
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
