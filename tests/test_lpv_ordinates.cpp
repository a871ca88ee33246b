// Discrete-ordinates transport (gi/lpv/ordinates.h): the bins tile the sphere, a plane never
// receives its own light, a patch lights a parallel receiver as the analytic view factor says,
// walls stop light, and bounces converge to the closed form of a closed box.
#include <gtest/gtest.h>

#include <cmath>

#include "gi/lpv/ordinates.h"
#include "shaders/shared/constants.h"

using namespace voxgi;
using shading::kPi;

namespace {

CascadeGrid gridOf(int n, float h = 1.0f) {
    CascadeGrid g;
    g.resolution = n;
    g.cellSize = h;
    return g;
}

// A layer of floor cells at y = `layer` over x, z in [lo, hi): each a surface of full coverage
// facing +y, and (when emitting) a surfel of exitance M at its centre.
void addFloor(OrdinatesTransport& t, int layer, int lo, int hi, float albedo) {
    for (int z = lo; z < hi; ++z)
        for (int x = lo; x < hi; ++x) t.addSurface({{x, layer, z}, 1.0f, {0.0f, 1.0f, 0.0f}, glm::vec3(albedo)});
}
SurfelSource floorSurfels(int layer, int lo, int hi, float exitance, float h = 1.0f) {
    SurfelSource s;
    for (int z = lo; z < hi; ++z)
        for (int x = lo; x < hi; ++x) {
            Surfel f;
            f.position = (glm::vec3(float(x), float(layer), float(z)) + 0.5f) * h;
            f.normal = {0.0f, 1.0f, 0.0f};
            f.flux = glm::vec3(exitance * h * h);
            f.area = h * h;
            s.surfels.push_back(f);
        }
    return s;
}

// Irradiance at the centre of a point facing a parallel square of half-side b at distance d,
// exitance 1: four corner rectangles of the differential-area-to-rectangle view factor.
double squareViewFactor(double b, double d) {
    const double x = b / d, y = b / d;
    const double sx = std::sqrt(1 + x * x), sy = std::sqrt(1 + y * y);
    const double corner = (x / sx * std::atan(y / sx) + y / sy * std::atan(x / sy)) / (2.0 * kPi);
    return 4.0 * corner;
}

}  // namespace

TEST(LpvOrdinates, BinsTileTheSphereAndNoneStraddlesAnAxisPlane) {
    for (int perFace : {2, 4}) {
        const std::vector<OrdinateBin> bins = makeOrdinateBins(perFace);
        ASSERT_EQ(bins.size(), std::size_t(6 * perFace * perFace));
        double solid = 0.0;
        for (const OrdinateBin& b : bins) {
            solid += b.solidAngle;
            EXPECT_NEAR(b.taps[0] + b.taps[1] + b.taps[2] + b.taps[3], 1.0f, 1e-5f);
            for (int a = 0; a < 3; ++a) EXPECT_NE(b.moment[a], 0.0f) << "a bin with no sign along an axis straddles it";
        }
        EXPECT_NEAR(solid, 4.0 * kPi, 1e-3);
        // Every axis hemisphere is covered exactly: the cosine-weighted sum is pi.
        for (int a = 0; a < 3; ++a)
            for (float sign : {1.0f, -1.0f}) {
                glm::vec3 n(0.0f);
                n[a] = sign;
                double cosine = 0.0;
                for (const OrdinateBin& b : bins) cosine += std::max(0.0f, glm::dot(n, b.moment));
                EXPECT_NEAR(cosine, kPi, 1e-3) << perFace << " axis " << a;
            }
    }
    std::vector<float> shares;
    emissionShares(makeOrdinateBins(2), glm::normalize(glm::vec3(0.3f, 0.8f, -0.2f)), shares);
    double sum = 0.0;
    for (float s : shares) sum += s;
    EXPECT_NEAR(sum, 1.0, 1e-5);
}

// The cause this transport removes: a lit floor with nothing above it receives nothing.
TEST(LpvOrdinates, ALitFloorAloneReceivesNoneOfItsOwnLight) {
    OrdinatesTransport t(gridOf(16), 2);
    addFloor(t, 2, 0, 16, 0.8f);
    OrdinatesTransport::Sources s = t.emptySources();
    t.addSurfels(floorSurfels(2, 0, 16, 1.0f), 0.0f, s);
    const auto e = t.solve(s, true, 8);
    double up = 0.0, downAbove = 0.0;
    for (int z = 0; z < 16; ++z)
        for (int x = 0; x < 16; ++x)
            for (int y = 2; y < 5; ++y) {
                up += e[2][t.grid().index({x, y, z})].r;         // receivers facing +y: the floor's
                downAbove += e[3][t.grid().index({x, y, z})].r;  // facing -y: a ceiling above it would get
            }
    EXPECT_EQ(up, 0.0);
    EXPECT_GT(downAbove, 0.0);
}

// A square patch of exitance 1 and a receiver above its centre facing it: the view factor.
TEST(LpvOrdinates, APatchLightsAParallelReceiverAsTheViewFactorSays) {
    const int n = 64, lo = 16, hi = 48;
    OrdinatesTransport t(gridOf(n), 4);
    addFloor(t, 0, lo, hi, 0.0f);
    // Sweeps visit the surfaces' bounds only (sweepBox): a black speck away from the centre line
    // takes them up to the heights read, stopping a millionth of what crosses its cell.
    t.addSurface({{lo, 40, lo}, 1e-6f, {0.0f, -1e-6f, 0.0f}, glm::vec3(0.0f)});
    EXPECT_EQ(t.sweepBox().max.y, 40 + kSweepMargin);
    OrdinatesTransport::Sources s = t.emptySources();
    t.addSurfels(floorSurfels(0, lo, hi, 1.0f), 0.0f, s);
    const auto e = t.solve(s, true, 1);
    // Above the box nothing is swept.
    EXPECT_EQ(e[3][t.grid().index({32, 50, 32})].r, 0.0f);
    for (int height : {4, 8, 16, 32}) {
        // Four cells around the patch's centre line.
        double sum = 0.0;
        for (int dz = 31; dz <= 32; ++dz)
            for (int dx = 31; dx <= 32; ++dx) sum += e[3][t.grid().index({dx, height, dz})].r;
        const double measured = sum / 4.0, expected = squareViewFactor(16.0, double(height));
        EXPECT_NEAR(measured / expected, 1.0, 0.1) << "height " << height << ": " << measured << " vs " << expected;
    }
}

// A one-cell wall between a lit floor patch and the other side stops its light.
TEST(LpvOrdinates, AWallStopsTheLightBehindIt) {
    const int n = 32;
    OrdinatesTransport t(gridOf(n), 2);
    addFloor(t, 0, 0, n, 0.0f);
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y) t.addSurface({{16, y, z}, 1.0f, {-1.0f, 0.0f, 0.0f}, glm::vec3(0.0f)});
    OrdinatesTransport::Sources s = t.emptySources();
    SurfelSource lit;
    for (const Surfel& f : floorSurfels(0, 0, 16, 1.0f).surfels) lit.surfels.push_back(f);
    t.addSurfels(lit, 0.0f, s);
    const auto e = t.solve(s, true, 1);
    double front = 0.0, behind = 0.0;
    for (int z = 0; z < n; ++z)
        for (int y = 4; y < 12; ++y) {
            front += e[3][t.grid().index({8, y, z})].r;
            behind += e[3][t.grid().index({24, y, z})].r;
        }
    EXPECT_GT(front, 0.0);
    EXPECT_LT(behind, 1e-6 * front) << "rounding only";
}

// A closed cube of albedo a lit by sources of power P: everything emitted is eventually absorbed,
// so the walls receive P / (1 - a) over all bounces and reflect a P / (1 - a); a leak would lose it.
TEST(LpvOrdinates, BouncesInAClosedBoxSumToTheGeometricSeries) {
    const int n = 12;
    for (float albedo : {0.5f, 0.9f}) {
        OrdinatesTransport t(gridOf(n), 2);
        for (int a = 0; a < n; ++a)
            for (int b = 0; b < n; ++b) {
                t.addSurface({{a, b, 0}, 1.0f, {0, 0, 1}, glm::vec3(albedo)});
                t.addSurface({{a, b, n - 1}, 1.0f, {0, 0, -1}, glm::vec3(albedo)});
                t.addSurface({{a, 0, b}, 1.0f, {0, 1, 0}, glm::vec3(albedo)});
                t.addSurface({{a, n - 1, b}, 1.0f, {0, -1, 0}, glm::vec3(albedo)});
                t.addSurface({{0, a, b}, 1.0f, {1, 0, 0}, glm::vec3(albedo)});
                t.addSurface({{n - 1, a, b}, 1.0f, {-1, 0, 0}, glm::vec3(albedo)});
            }
        OrdinatesTransport::Sources s = t.emptySources();
        t.addSurfels(floorSurfels(0, 1, n - 1, 1.0f), 0.0f, s);
        const auto first = t.solve(s, true, 1000);
        const OrdinatesStats& st = t.stats();
        EXPECT_GT(st.sweeps, 5);
        EXPECT_NEAR(st.reflectedWatts / st.emittedWatts, albedo / (1.0 - albedo), 0.01 * albedo / (1.0 - albedo))
            << "albedo " << albedo << ", " << st.sweeps << " sweeps";
        // The same bits again, whichever threads swept which bins.
        const auto again = t.solve(s, true, 1000);
        for (int f = 0; f < kOrdinateFaces; ++f)
            EXPECT_TRUE(first[std::size_t(f)] == again[std::size_t(f)]) << "face " << f;
    }
}

// lpv.sweeps=N: one sweep per update, carrying the last sweep's reflections into the next,
// reaches the all-bounces solution over updates (a fixed point), and is short of it at first.
TEST(LpvOrdinates, OneSweepPerUpdateConvergesToEveryBounceOverUpdates) {
    const int n = 10;
    OrdinatesTransport t(gridOf(n), 2);
    for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) {
            t.addSurface({{a, 0, b}, 1.0f, {0, 1, 0}, glm::vec3(0.6f)});
            t.addSurface({{a, n - 1, b}, 1.0f, {0, -1, 0}, glm::vec3(0.6f)});
            t.addSurface({{0, a, b}, 1.0f, {1, 0, 0}, glm::vec3(0.6f)});
        }
    OrdinatesTransport::Sources s = t.emptySources();
    t.addSurfels(floorSurfels(0, 2, n - 2, 1.0f), 0.0f, s);
    auto floorLight = [&](const std::array<std::vector<glm::vec4>, kOrdinateFaces>& e) {
        double sum = 0.0;
        for (int z = 1; z < n - 1; ++z)
            for (int x = 1; x < n - 1; ++x) sum += e[2][t.grid().index({x, 0, z})].r;
        return sum;
    };
    const double full = floorLight(t.solve(s, true, 1000));
    std::vector<glm::vec3> carry;
    const double first = floorLight(t.solve(s, true, 1, &carry));
    EXPECT_LT(first, 0.5 * full) << "the floor's light is all bounce light";
    double last = first;
    for (int update = 1; update < 40; ++update) last = floorLight(t.solve(s, true, 1, &carry));
    // The full solve stops once a sweep would carry under 1e-3 of the sources' power, leaving out
    // up to 1e-3 x a / (1 - a) of the light: the carried updates end slightly above it.
    EXPECT_NEAR(last / full, 1.0, 3e-3);
}

// The sky's bounce off every surface (lpv.sky_bounce with ordinates): a floor cell lit with 2 W/m^2
// reflects albedo x irradiance x area, into the bins that travel up; a thin plate whose two sides
// cancel in one voxel reflects nothing (its sides are unknown).
TEST(LpvOrdinates, SurfacesReflectTheIrradianceTheyAreGivenIntoTheirHemisphere) {
    OrdinatesTransport t(gridOf(8, 0.5f), 2);
    t.addSurface({{2, 1, 2}, 1.0f, {0.0f, 1.0f, 0.0f}, glm::vec3(0.5f)});
    t.addSurface({{5, 5, 5}, 2.0f, {0.0f, 0.0f, 0.0f}, glm::vec3(0.5f)});
    OrdinatesTransport::Sources s = t.emptySources();
    glm::vec3 seenNormal(0.0f);
    t.addReflectedIrradiance(
        [&](glm::vec3, glm::vec3 n) {
            seenNormal = n;
            return glm::vec3(2.0f);
        },
        [](glm::vec3) { return 1.0f; }, s);
    EXPECT_NEAR(s.watts, 3.0 * 0.5 * 2.0 * 0.25, 1e-6);  // three colours, 0.25 m^2
    EXPECT_EQ(seenNormal, glm::vec3(0.0f, 1.0f, 0.0f));
    const std::size_t nb = t.bins().size(), floor = std::size_t(t.surfaceIndex({2, 1, 2}));
    for (std::size_t k = 0; k < nb; ++k) {
        if (t.bins()[k].moment.y >= 0.0f) continue;
        EXPECT_EQ(s.power[(floor * nb + k) * 3], 0.0f) << "bin " << k;
    }
}

// Sweeps visit only the surfaces' bounds plus a margin (sweepBox): light leaving them never comes
// back, so a volume three times wider gives its surfaces the same light, bit for bit, over every
// bounce, and nothing outside the box.
TEST(LpvOrdinates, TheSweepBoxGivesTheSameLightAsAVolumeFittedToTheSurfaces) {
    const int fit = 12, wide = 36;
    auto build = [&](int n) {
        OrdinatesTransport t(gridOf(n), 2);
        addFloor(t, 0, 0, fit, 0.6f);
        for (int z = 0; z < fit; ++z)
            for (int y = 1; y < fit; ++y) t.addSurface({{fit - 1, y, z}, 1.0f, {-1.0f, 0.0f, 0.0f}, glm::vec3(0.5f)});
        return t;
    };
    OrdinatesTransport tight = build(fit), big = build(wide);
    EXPECT_EQ(big.sweepBox().min, glm::ivec3(0));
    EXPECT_EQ(big.sweepBox().max, glm::ivec3(fit - 1 + kSweepMargin));
    EXPECT_EQ(tight.sweepBox().max, glm::ivec3(fit - 1));  // clipped to the grid
    OrdinatesTransport::Sources a = tight.emptySources(), b = big.emptySources();
    tight.addSurfels(floorSurfels(0, 2, 6, 1.0f), 0.0f, a);
    big.addSurfels(floorSurfels(0, 2, 6, 1.0f), 0.0f, b);
    const auto ea = tight.solve(a, true, 8), eb = big.solve(b, true, 8);
    EXPECT_EQ(tight.stats().sweeps, big.stats().sweeps);
    double lit = 0.0;
    for (int f = 0; f < kOrdinateFaces; ++f)
        for (int z = 0; z < fit; ++z)
            for (int y = 0; y < fit; ++y)
                for (int x = 0; x < fit; ++x)
                    if (tight.surfaceIndex({x, y, z}) >= 0) {
                        const glm::vec4 va = ea[std::size_t(f)][tight.grid().index({x, y, z})];
                        const glm::vec4 vb = eb[std::size_t(f)][big.grid().index({x, y, z})];
                        ASSERT_EQ(va, vb) << "face " << f << " cell " << x << " " << y << " " << z;
                        lit += va.r;
                    }
    EXPECT_GT(lit, 0.0);
    EXPECT_EQ(eb[0][big.grid().index({wide - 1, wide - 1, wide - 1})], glm::vec4(0.0f));
}
