// Discrete-ordinates transport (gi/lpv/ordinates.h): the bins tile the sphere, a plane never
// receives its own light, a patch lights a parallel receiver as the analytic view factor says,
// walls stop light, and bounces converge to the closed form of a closed box.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "gi/lpv/ordinates.h"
#include "gi/lpv/tap_masks.h"
#include "gi/raytrace/ray_tracer.h"
#include "scenes/scene_loader.h"
#include "gi/sampling/sequences.h"
#include "shaders/shared/irradiance_cube.h"
#include "shaders/shared/light_bricks.h"
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
TEST(LpvOrdinates, BundlesHoldEveryBinOnceAndOnlyBinsWhoseMovesAreAlike) {
    for (int perFace : {2, 4, 6}) {
        const OrdinatesTransport t(gridOf(8), perFace, kSweepMargin);
        const std::vector<OrdinateBin>& bins = t.bins();
        std::vector<int> seen(bins.size(), 0);
        std::size_t full = 0;
        for (const std::vector<std::size_t>& bundle : t.sweepBundles()) {
            ASSERT_FALSE(bundle.empty());
            ASSERT_LE(bundle.size(), kSweepLanes);
            full += bundle.size() == kSweepLanes;
            for (std::size_t k : bundle) {
                ++seen[k];
                EXPECT_EQ(bins[k].axis, bins[bundle.front()].axis);
                EXPECT_EQ(bins[k].sign, bins[bundle.front()].sign);
                EXPECT_EQ(bins[k].lateralStep, bins[bundle.front()].lateralStep);
            }
        }
        for (int count : seen) EXPECT_EQ(count, 1);
        // A quadrant of a face holds (perFace / 2)^2 bins: lpv's 2 per face one bin a bundle,
        // clpv's 4 exactly one full bundle per quadrant.
        if (perFace == 2) {
            EXPECT_EQ(t.sweepBundles().size(), bins.size());
        }
        if (perFace == 4) {
            EXPECT_EQ(full * kSweepLanes, bins.size());
        }
    }
}

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
                up += t.irradianceAt(e, {x, y, z}, 2).r;         // receivers facing +y: the floor's
                downAbove += t.irradianceAt(e, {x, y, z}, 3).r;  // facing -y: a ceiling above it would get
            }
    EXPECT_EQ(up, 0.0);
    EXPECT_GT(downAbove, 0.0);
}

// A square patch of exitance 1 and a receiver above its centre facing it: the view factor.
TEST(LpvOrdinates, APatchLightsAParallelReceiverAsTheViewFactorSays) {
    const int n = 64, lo = 16, hi = 48;
    OrdinatesTransport t(gridOf(n), 4);
    t.allocateAllBricks();  // free space is read here, not only around surfaces
    addFloor(t, 0, lo, hi, 0.0f);
    // Sweeps visit the surfaces' bounds only (sweepBox): a black speck away from the centre line
    // takes them up to the heights read, stopping a millionth of what crosses its cell.
    t.addSurface({{lo, 40, lo}, 1e-6f, {0.0f, -1e-6f, 0.0f}, glm::vec3(0.0f)});
    EXPECT_EQ(t.sweepBox().max.y, 40 + kSweepMargin);
    OrdinatesTransport::Sources s = t.emptySources();
    t.addSurfels(floorSurfels(0, lo, hi, 1.0f), 0.0f, s);
    const auto e = t.solve(s, true, 1);
    // Above the box nothing is swept.
    EXPECT_EQ(t.irradianceAt(e, {32, 50, 32}, 3).r, 0.0f);
    for (int height : {4, 8, 16, 32}) {
        // Four cells around the patch's centre line.
        double sum = 0.0;
        for (int dz = 31; dz <= 32; ++dz)
            for (int dx = 31; dx <= 32; ++dx) sum += t.irradianceAt(e, {dx, height, dz}, 3).r;
        const double measured = sum / 4.0, expected = squareViewFactor(16.0, double(height));
        EXPECT_NEAR(measured / expected, 1.0, 0.1) << "height " << height << ": " << measured << " vs " << expected;
    }
}

// A one-cell wall between a lit floor patch and the other side stops its light.
TEST(LpvOrdinates, AWallStopsTheLightBehindIt) {
    const int n = 32;
    OrdinatesTransport t(gridOf(n), 2);
    t.allocateAllBricks();  // free space is read here, not only around surfaces
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
            front += t.irradianceAt(e, {8, y, z}, 3).r;
            behind += t.irradianceAt(e, {24, y, z}, 3).r;
        }
    EXPECT_GT(front, 0.0);
    EXPECT_LT(behind, 1e-6 * front) << "rounding only";
}

// A layer of cells each holding a vertical column (a closed surface whose normals are horizontal:
// no net normal, area S, projected coverage P = (p, 0, p) with S = p pi / 2) between black emitters
// and receivers. Light moving up passes the columns where it only crosses the layer's y faces and
// loses at most the mean shadow p / 2 over the faces a move crosses; light moving sideways loses at
// least that. Not knowing P (normals spread evenly) every move loses S / 4.
TEST(LpvOrdinates, AColonnadeLetsLightPassAlongItsColumnsAndStopsWhatCrossesThem) {
    const int n = 32;
    const float p = 0.8f, area = p * float(kPi) / 2.0f;
    // Light emitted by the plane `along` = 0 towards +along, crossing a layer of columns at
    // `along` = 8 (none when `columns` is false), received at 16..23 by faces facing -along, up to a
// black plane at 28. (Nearer the layer the grazing bins of the other axes add light that slid
// along the layer, through several of its cells.)
    auto received = [&](int along, bool columns, glm::vec3 projected) {
        OrdinatesTransport t(gridOf(n), 2);
        t.allocateAllBricks();
        auto cell = [&](int a, int x, int y) {
            glm::ivec3 c;
            c[along] = a;
            c[(along + 1) % 3] = x;
            c[(along + 2) % 3] = y;
            return c;
        };
        glm::vec3 normal(0.0f);
        normal[along] = 1.0f;
        SurfelSource emitters;
        for (int x = 0; x < n; ++x)
            for (int y = 0; y < n; ++y) {
                t.addSurface({cell(0, x, y), 1.0f, normal, glm::vec3(0.0f)});
                t.addSurface({cell(28, x, y), 1.0f, -normal, glm::vec3(0.0f)});  // the sweeps reach it
                if (columns) t.addSurface({cell(8, x, y), area, glm::vec3(0.0f), glm::vec3(0.0f), projected});
                Surfel f;
                f.position = glm::vec3(cell(0, x, y)) + 0.5f;
                f.normal = normal;
                f.flux = glm::vec3(1.0f);
                f.area = 1.0f;
                emitters.surfels.push_back(f);
            }
        OrdinatesTransport::Sources s = t.emptySources();
        t.addSurfels(emitters, 0.0f, s);
        const auto e = t.solve(s, true, 1);
        double sum = 0.0;
        for (int a = 16; a < 24; ++a)
            for (int x = 8; x < 24; ++x)
                for (int y = 8; y < 24; ++y) sum += t.irradianceAt(e, cell(a, x, y), 2 * along + 1).r;
        return sum;
    };
    const glm::vec3 column(p, 0.0f, p), unknown(0.0f);
    const double up = received(1, true, column) / received(1, false, column);
    const double sideways = received(0, true, column) / received(0, false, column);
    const double evenly = received(1, true, unknown) / received(1, false, unknown);
    EXPECT_NEAR(evenly, 1.0 - area / 4.0, 1e-4);
    EXPECT_GT(up, 1.0 - p / 3.0);  // taps crossing y and one or two lateral faces lose p/4 or p/3
    EXPECT_LT(up, 1.0);            // ... and some taps do
    EXPECT_GT(up, evenly);
    EXPECT_LE(sideways, 1.0 - p / 4.0 + 1e-4);  // every sideways move loses at least p / 4
    EXPECT_GE(sideways, 1.0 - p / 2.0 - 1e-4);
    EXPECT_LT(sideways, up - 0.05);
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
        EXPECT_TRUE(first == again);
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
    auto floorLight = [&](const IrradianceBricks& e) {
        double sum = 0.0;
        for (int z = 1; z < n - 1; ++z)
            for (int x = 1; x < n - 1; ++x) sum += t.irradianceAt(e, {x, 0, z}, 2).r;
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
                        const glm::vec4 va = tight.irradianceAt(ea, {x, y, z}, f);
                        const glm::vec4 vb = big.irradianceAt(eb, {x, y, z}, f);
                        ASSERT_EQ(va, vb) << "face " << f << " cell " << x << " " << y << " " << z;
                        lit += va.r;
                    }
    EXPECT_GT(lit, 0.0);
    EXPECT_EQ(big.irradianceAt(eb, {wide - 1, wide - 1, wide - 1}, 0), glm::vec4(0.0f));
}

// Sparse light volumes (gi/lpv/brick_map.h): bricks are stored only within the receivers' reach of
// a surface, and hold there exactly what storing every brick holds.
TEST(LpvOrdinates, BricksAroundTheSurfacesHoldWhatEveryBrickHolds) {
    const int n = 40;  // not a multiple of 8: the last bricks are partial
    auto build = [&](OrdinatesTransport& t) {
        std::vector<OrdinateSurface> surfaces;
        for (int z = 4; z < 20; ++z)
            for (int x = 4; x < 20; ++x) surfaces.push_back({{x, 3, z}, 1.0f, {0.0f, 1.0f, 0.0f}, glm::vec3(0.7f)});
        for (int z = 4; z < 20; ++z)
            for (int y = 3; y < 20; ++y) surfaces.push_back({{20, y, z}, 1.0f, {-1.0f, 0.0f, 0.0f}, glm::vec3(0.5f)});
        t.addSurfaces(surfaces);
    };
    OrdinatesTransport sparse(gridOf(n), 2), dense(gridOf(n), 2);
    dense.allocateAllBricks();
    build(sparse);
    build(dense);
    EXPECT_EQ(dense.bricks().slots(), 125u);
    EXPECT_LT(sparse.bricks().slots(), dense.bricks().slots() / 2) << "bricks far from the surfaces are stored";
    EXPECT_GT(sparse.bricks().slots(), 0u);
    OrdinatesTransport::Sources a = sparse.emptySources(), b = dense.emptySources();
    sparse.addSurfels(floorSurfels(3, 4, 20, 1.0f), 0.0f, a);
    dense.addSurfels(floorSurfels(3, 4, 20, 1.0f), 0.0f, b);
    const IrradianceBricks ea = sparse.solve(a, true, 100), eb = dense.solve(b, true, 100);
    EXPECT_EQ(sparse.stats().sweeps, dense.stats().sweeps);
    EXPECT_EQ(ea.size(), sparse.bricks().slots() * 6 * 512);
    std::size_t stored = 0, near = 0;
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const glm::ivec3 c(x, y, z);
                // Within the reach of a surface (the floor's and the wall's boxes, kSweepMargin wider).
                const bool nearFloor = x >= 4 - kSweepMargin && x < 20 + kSweepMargin && z >= 4 - kSweepMargin &&
                                       z < 20 + kSweepMargin && std::abs(y - 3) <= kSweepMargin;
                const bool nearWall = std::abs(x - 20) <= kSweepMargin && y >= 3 - kSweepMargin && y < 20 + kSweepMargin &&
                                      z >= 4 - kSweepMargin && z < 20 + kSweepMargin;
                if (nearFloor || nearWall) {
                    ++near;
                    ASSERT_GE(sparse.bricks().slotOf(c), 0) << "a receiver's cell is not stored: " << x << " " << y << " " << z;
                }
                if (sparse.bricks().slotOf(c) < 0) continue;
                ++stored;
                for (int f = 0; f < kOrdinateFaces; ++f)
                    ASSERT_EQ(sparse.irradianceAt(ea, c, f), dense.irradianceAt(eb, c, f))
                        << "face " << f << " cell " << x << " " << y << " " << z;
            }
    EXPECT_GT(near, 0u);
    std::size_t inGrid = 0;  // the stored bricks' cells inside the grid
    for (const glm::ivec3& o : sparse.bricks().slotOrigins()) {
        const glm::ivec3 e = glm::min(o + 8, glm::ivec3(n)) - o;
        inGrid += std::size_t(e.x) * std::size_t(e.y) * std::size_t(e.z);
    }
    EXPECT_EQ(stored, inGrid);
}

// The bricks' layout: 8^3 cells from the grid's first cell, x fastest.
TEST(LpvOrdinates, ABricksCellsRunXFastest) {
    EXPECT_EQ(shading::brickCellOffset(glm::ivec3(1, 0, 0)), 1);
    EXPECT_EQ(shading::brickCellOffset(glm::ivec3(0, 1, 0)), 8);
    EXPECT_EQ(shading::brickCellOffset(glm::ivec3(0, 0, 1)), 64);
    EXPECT_EQ(shading::brickCellOffset(glm::ivec3(15, 9, 23)), 7 + 1 * 8 + 7 * 64);
    EXPECT_EQ(shading::bricksPerSide(40), 5);
    BrickMap map(40);
    map.allocateAround(std::vector<glm::ivec3>{{39, 0, 0}, {0, 0, 0}}, 0);
    // Slots in the table's order (x fastest), whichever cell asked first.
    ASSERT_EQ(map.slots(), 2u);
    EXPECT_EQ(map.slotOrigins()[0], glm::ivec3(0));
    EXPECT_EQ(map.slotOrigins()[1], glm::ivec3(32, 0, 0));
    EXPECT_EQ(map.slotOf({33, 7, 7}), 1);
    EXPECT_EQ(map.slotOf({33, 8, 7}), -1);
    EXPECT_EQ(map.slotOf({40, 0, 0}), -1);
}

namespace {

// A receiver's irradiance from six face values by shading::cubeWeights.
float readCube(const float faces[6], glm::vec3 n, bool quadratic) {
    const shading::CubeWeights w = shading::cubeWeights(n, quadratic);
    float e = 0.0f;
    for (int a = 0; a < 3; ++a) e += w.towards[a] * faces[2 * a] + w.against[a] * faces[2 * a + 1];
    return e;
}

}  // namespace

// How receivers read a cell's six axis faces (shaders/shared/irradiance_cube.h): both reads give
// each face's value on its axis normal and a uniform field's irradiance for every normal. Under a
// hemisphere of uniform radiance (a sky, a large lit wall) the irradiance is linear in the normal,
// pi L (1 + n . d) / 2, which the quadratic reads exactly for every normal while the ambient
// cube's n^2 blend is off by up to a fifth of it for tilted normals.
TEST(LpvCubeRead, TheQuadraticReadsAHemisphereOfLightExactlyForEveryNormal) {
    for (bool quadratic : {false, true}) {
        SCOPED_TRACE(quadratic ? "quadratic" : "ambient");
        const float faces[6] = {1.0f, 2.0f, 3.0f, 4.0f, 5.0f, 6.0f};
        for (int f = 0; f < 6; ++f) {
            glm::vec3 n(0.0f);
            n[f / 2] = f % 2 == 0 ? 1.0f : -1.0f;
            EXPECT_FLOAT_EQ(readCube(faces, n, quadratic), faces[f]) << "face " << f;
        }
        const float uniform[6] = {2.5f, 2.5f, 2.5f, 2.5f, 2.5f, 2.5f};
        for (int i = 0; i < 64; ++i) EXPECT_NEAR(readCube(uniform, sphericalFibonacci(i, 64), quadratic), 2.5f, 1e-5f);
    }
    float worstAmbient = 0.0f, worstQuadratic = 0.0f;
    for (int j = 0; j < 16; ++j) {
        const glm::vec3 d = sphericalFibonacci(j, 16);  // the hemisphere's axis
        float faces[6];
        for (int f = 0; f < 6; ++f) faces[f] = kPi * (1.0f + (f % 2 == 0 ? d[f / 2] : -d[f / 2])) / 2.0f;
        for (int i = 0; i < 256; ++i) {
            const glm::vec3 n = sphericalFibonacci(i, 256);
            const float truth = kPi * (1.0f + glm::dot(n, d)) / 2.0f;
            worstAmbient = std::max(worstAmbient, std::abs(readCube(faces, n, false) - truth) / kPi);
            worstQuadratic = std::max(worstQuadratic, std::abs(readCube(faces, n, true) - truth) / kPi);
        }
    }
    EXPECT_LT(worstQuadratic, 1e-5f);
    EXPECT_GT(worstAmbient, 0.1f);
}

// lpv.tap_visibility=cells: two parallel walls 0.7 m apart across 1 m cells. The side of the first
// wall that faces the second sees nothing beyond it (the cells one step along +x), and keeps the
// cells behind itself; its other side faces open space and sees everything; a cell without
// surfaces sees everything.
TEST(LpvOrdinates, TapMasksSeeTheCellsInFrontOfASideAndKeepThoseBehindIt) {
    Scene s = parseSceneJson(R"({"camera": {"eye": [1, 1, 1], "target": [4, 4, 4]},
        "materials": {"stone": {"albedo": 0.5}},
        "meshes": [{"type": "quad", "material": "stone", "corners": [[3.5, 0, 0], [3.5, 8, 0], [3.5, 8, 8], [3.5, 0, 8]]},
                   {"type": "quad", "material": "stone", "corners": [[4.2, 0, 0], [4.2, 8, 0], [4.2, 8, 8], [4.2, 0, 8]]}]})",
                             "walls.json");
    CascadeGrid grid;
    grid.resolution = 8;
    grid.cellSize = 1.0f;
    BrickMap bricks(8);
    bricks.allocateAll();
    RayTracer tracer(s);
    const TapMasks masks = traceTapMasks(s, tracer, grid, bricks);
    // The mask a receiver at p facing n reads: its cell's, for the half cell p lies in.
    auto maskAt = [&](glm::vec3 p, glm::vec3 n) {
        const glm::ivec3 cell = grid.cellOf(p);
        const std::int32_t first = masks.cells[BrickMap::brickCell(bricks.slotOf(cell), cell)];
        if (first < 0) return kAllTapBits;
        const glm::ivec3 half = glm::ivec3(glm::floor((p - glm::floor(p)) * 2.0f));
        return masks.masks[std::size_t(first) * kTapMasksPerCell + std::size_t((half.x + 2 * half.y + 4 * half.z) * 6) +
                           std::size_t(tapMaskClass(n))];
    };
    EXPECT_EQ(tapMaskClass({0.2f, -0.9f, 0.1f}), 3);  // -y
    EXPECT_EQ(tapMaskClass({0.5f, 0.5f, 0.5f}), 0);   // ties go to x
    const glm::vec3 wall(3.5f, 4.25f, 4.7f);
    const std::uint32_t facing = maskAt(wall, {1, 0, 0}), away = maskAt(wall, {-1, 0, 0});
    for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy) {
            EXPECT_FALSE((facing >> tapMaskBit({1, dy, dz})) & 1u) << "beyond the second wall " << dy << " " << dz;
            EXPECT_TRUE((facing >> tapMaskBit({-1, dy, dz})) & 1u) << "behind the first wall " << dy << " " << dz;
            EXPECT_TRUE((facing >> tapMaskBit({0, dy, dz})) & 1u) << "its own column " << dy << " " << dz;
        }
    EXPECT_EQ(away, kAllTapBits);
    EXPECT_EQ(maskAt({1.5f, 4.5f, 4.5f}, {1, 0, 0}), kAllTapBits);
    EXPECT_EQ(masks.cells[BrickMap::brickCell(bricks.slotOf({1, 4, 4}), {1, 4, 4})], -1);
}
