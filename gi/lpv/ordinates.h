// Discrete-ordinates transport for the light volumes (`lpv.transport=ordinates`): the light is
// kept in direction bins on its way from surface to surface, instead of being re-emitted as a
// hemisphere-wide 2-band SH lobe at every cell.
//
// Why (docs/lpv.md, "Self-illumination"): SH propagation turns light that leaves a surface
// sideways back towards that surface within a few cells, so a sunlit floor lights itself (Sponza's
// floor got 10-25x the path tracer's indirect light); more SH bands or re-emission along each
// face's central direction removed a fifth of it at most. Here a bin's light only moves
// downstream along its own directions, and no bin straddles an axis plane, so a plane along an
// axis never receives its own light: a floor emits into the bins that travel upwards and reads the
// bins that travel downwards.
//
// Bins: each cube face's pyramid of directions (the axis with the largest |component|) is split
// into perFace x perFace squares of the two lateral slopes (lateral component / |axis
// component|, each in [-1, 1]). A bin is swept slab by slab along its axis; its power moves to
// the next slab and spreads over 2 x 2 lateral cells with the probabilities that a ray of the
// bin, entering its cell at a uniform point, lands there (first-order upwind, averaged over the
// bin). One sweep carries light across the whole volume, so there is no step count; each further
// sweep adds one bounce.
//
// Units: a cell holds the power (W) its bin carries across one slab. The power entering a cell
// through its faces of axis a, over h^2, is the irradiance on a surface facing against that move:
// in free space that equals the bin's radiance (power / (h^2 * integral over the bin of
// |w_axis|)) times its cosine moment, and in a cell whose surfaces stop light it counts only what
// crosses into the cell, as a surface there receives it (a radiance estimate there read the
// grazing light twice attenuated: walls came out at 0.7 of the path tracer). Each cell stores
// this irradiance for the six axis normals (an irradiance cube); a receiver blends the three
// faces its normal points along by n^2 or reads the quadratic in n that takes the six values on
// the axis normals (lpv.cube_read; shaders/shared/irradiance_cube.h, apply_ordinates.frag).
//
// Surfaces: each cell's coverage S (area / h^2), vector coverage m (area x normal / h^2) and
// projected coverage P (per axis a, area x |n_a| / h^2) from the voxelizer. A tap's move into a
// cell crosses the slab face and possibly side faces; the cell's surfaces stop the fraction sum
// over the crossed axes a of |m_a| (the surfaces of one orientation: a floor stops what moves up
// or down into its cell, not what slides along it, so light neither leaks through a one-cell wall
// nor is stopped by surfaces it runs parallel to), plus the mean over the crossed axes of the
// shadow (P_a - |m_a|) / 2 of the surfaces whose normals cancel (clutter, both sides of a thin
// plate: a closed surface seen along an axis hides half of its projected area P_a, each part of it
// being seen from both sides; the mean, because a small object's shadow over a cell's cross-section
// does not grow with the faces a move crosses), at most all of it. So a colonnade's cells let
// light move up and down past the columns (P_y = 0) and stop what crosses them sideways; with
// normals spread evenly (P_a - |m_a| = (S - |m|) / 2 on every axis) the shadow is (S - |m|) / 4,
// a closed surface's mean projected area. A move out of a cell is stopped by the cell's surfaces
// that face against it (a corner cell's wall, for its floor's light). Stopped power times the
// albedo is reflected: by a cell whose surfaces share one orientation into its normal's
// hemisphere, else by each crossed axis's part of the surfaces into the hemisphere of the axis
// face the light arrived on (a cell holding a floor and a wall reflects up and sideways, never
// into either).
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "gi/lpv/brick_map.h"
#include "gi/lpv/light_volume.h"
#include "gi/lpv/surfels.h"
#include "volumes/geometry_volume.h"

namespace voxgi {

struct OrdinateBin {
    int axis = 0;                  // 0 x, 1 y, 2 z: the axis it is swept along
    int sign = 1;                  // +1: swept towards increasing coordinates
    glm::ivec2 lateralStep{1};     // +-1: the second tap's offset along (axis+1)%3 and (axis+2)%3
    std::array<float, 4> taps{};   // landing weights: (0, 0), (step.x, 0), (0, step.y), (step.x, step.y)
    glm::vec3 moment{0.0f};        // integral over the bin of w dw (sr)
    float solidAngle = 0.0f;       // sr
    float axisFlux = 0.0f;         // integral over the bin of |w_axis| dw (sr)
};

// 6 * perFace^2 bins (perFace even, so no bin straddles an axis plane).
std::vector<OrdinateBin> makeOrdinateBins(int perFace);

// Fractions of a Lambertian emitter's power (normal n) that each bin carries: max(n . moment, 0)
// normalized to sum to 1 (isotropic, by solid angle, when n is zero).
void emissionShares(const std::vector<OrdinateBin>& bins, glm::vec3 n, float* shares);
void emissionShares(const std::vector<OrdinateBin>& bins, glm::vec3 n, std::vector<float>& shares);

// The surfaces of one cell, as the voxelizer reports them (volumes/geometry_volume.h).
struct OrdinateSurface {
    glm::ivec3 cell{0};
    float coverage = 0.0f;            // sum of areas / h^2
    glm::vec3 vectorCoverage{0.0f};   // sum of area x unit normal / h^2
    glm::vec3 albedo{0.0f};
    // Per axis, area x |normal component| / h^2; zero: not known, estimated from S and m as if the
    // normals beyond m pointed every way evenly (isotropicProjectedCoverage).
    glm::vec3 projectedCoverage{0.0f};
};

// Axis faces of the irradiance cube: a receiver facing +x, -x, +y, -y, +z, -z.
constexpr int kOrdinateFaces = 6;

// Sweeps stop once the reflected light to carry is below this share of the sources' power: with
// albedo a the light left out is at most kOrdinatesConverged x a / (1 - a) of it (under 1 % up to
// a = 0.9). The cpu and gl back ends both stop here.
constexpr double kOrdinatesConverged = 1e-3;

// Cells a receiver reads around the surface cells at the default lookup offset: the apply pass
// reads a receiver's light half a cell along its normal, trilinearly (one cell further). The
// sweeps cover the surface cells' bounds this much wider and the bricks are allocated this far
// around every surface cell (ordinatesReach: more for a larger apply_normal_offset).
constexpr int kSweepMargin = 2;
// Bins one CPU sweep carries at once (OrdinatesTransport::sweepBundles).
constexpr std::size_t kSweepLanes = 4;

// The cells stored around each surface cell for a lookup `applyNormalOffsetCells` along the
// normal: the offset rounded up, plus one for the trilinear taps, at least kSweepMargin.
int ordinatesReach(float applyNormalOffsetCells);

// The irradiance cube of one volume, in its transport's bricks (gi/lpv/brick_map.h): face f of
// a cell at f x faceStride + brickCell (W/m^2, rgb, a = 0). Cells of bricks not
// allocated hold none: no receiver reads there.
using IrradianceBricks = std::vector<glm::vec4>;

struct OrdinatesStats {
    int sweeps = 0;                 // bounces solved (one sweep of every bin each)
    double emittedWatts = 0.0;      // the sources' power, summed over colours
    double reflectedWatts = 0.0;    // power reflected by the surfaces over all sweeps
    double leftWatts = 0.0;         // reflected by the last sweep and not carried (see solve's carry)
};

// One volume's transport: its grid, the bins and the cells' surfaces (kept while the geometry
// stays); sources are power per cell and bin, set per update.
class OrdinatesTransport {
public:
    // `reach`: the cells stored around each surface cell (ordinatesReach).
    OrdinatesTransport(const CascadeGrid& grid, int perFace, int reach = kSweepMargin);

    const CascadeGrid& grid() const { return grid_; }
    const std::vector<OrdinateBin>& bins() const { return bins_; }
    // The bricks that store light: every surface cell's, `reach` cells around it.
    const BrickMap& bricks() const { return bricks_; }
    // Stores every brick (lpv.sparse=false, or no voxelized scene to say where receivers are).
    void allocateAllBricks();
    // A cell's face of a solve's result (zero where no brick is allocated).
    glm::vec4 irradianceAt(const IrradianceBricks& e, glm::ivec3 cell, int face) const;

    // Adds a cell's surfaces (summed with any already there; albedo weighted by coverage).
    void addSurface(const OrdinateSurface& surface);
    // Adds many (the voxelized scene's), their bricks first, in the table's order.
    void addSurfaces(const std::vector<OrdinateSurface>& surfaces);
    std::size_t surfaceCells() const { return coverage_.size(); }

    // Sources: power (W, rgb) per surface cell and bin, indexed by surfaceIndex.
    struct Sources {
        std::vector<float> power;  // [surface][bin][rgb]
        double watts = 0.0;        // added, summed over colours
        double outsideWatts = 0.0; // surfels outside the grid
    };
    Sources emptySources() const;
    // Adds a surfel's flux at its position shifted `normalOffsetCells` along its normal, split over
    // the bins by `shares` (emissionShares of its normal, one per bin); a cell without surfaces
    // gets one. Outside the grid the flux is counted in outsideWatts.
    void addFlux(glm::vec3 position, glm::vec3 normal, glm::vec3 flux, const float* shares, float normalOffsetCells,
                 Sources& sources);
    // Every surfel of `source` (zero-flux ones skipped) with its own shares.
    void addSurfels(const SurfelSource& source, float normalOffsetCells, Sources& sources);
    // Every surface cell reflecting the irradiance `irradiance(point, normal)` (W/m^2) gives it
    // (the sky's, through the sky-lighting volume), times `weight(point)`, from its cell: a cell
    // of one orientation along its mean normal, others by each axis face's part. Normals that
    // cancel in a voxel (both sides of a thin plate) reflect nothing: their sides are unknown.
    template <typename Irradiance, typename Weight>
    void addReflectedIrradiance(Irradiance irradiance, Weight weight, Sources& sources);

    // Transports the sources and up to maxBounces - 1 reflections (stopping once a sweep would
    // carry less than 1e-3 of the sources' power); occlusion = false lets light pass every surface.
    // Returns the irradiance cube in the bricks.
    // `carry` (per surface and axis face, W): on entry, reflections an earlier solve left, carried
    // along with the sources (ignored when its size does not match); on return, the reflections of
    // the last sweep. Solving k sweeps per update with the carry converges to the full solution
    // over updates (a fixed point of sources + reflections), one bounce of lag per k sweeps.
    IrradianceBricks solve(const Sources& sources, bool occlusion, int maxBounces, std::vector<glm::vec3>* carry = nullptr);
    const OrdinatesStats& stats() const { return stats_; }

    // Where a blocker-free volume's source power goes: the cell index of a surface (for tests).
    int surfaceIndex(glm::ivec3 cell) const;

    // The layout the GL back end uploads (gi/lpv/gl_ordinates.h): per brick slot and cell its
    // surface index or -1 ([slot][kBrickCells]); per surface its coverage, vector coverage, clutter
    // shadow and albedo; per surface the shares of its
    // one-plane reflection over the bins (empty where its normals differ), and per axis face the
    // shares of its hemisphere.
    const std::vector<int>& surfaceOfBrickCells() const { return surfaceOf_; }
    const std::vector<float>& coverage() const { return coverage_; }
    const std::vector<glm::vec3>& vectorCoverage() const { return vectorCoverage_; }
    // Per axis, the shadow (P_a - |m_a|) / 2 of surface s's surfaces whose normals cancel (halves'
    // rounding may put P an ulp below |m|).
    glm::vec3 clutterShadow(std::size_t s) const {
        return 0.5f * glm::max(projected_[s] - glm::abs(vectorCoverage_[s]), glm::vec3(0.0f));
    }
    const std::vector<glm::vec3>& albedo() const { return albedo_; }
    // Changes whenever the surfaces do (a surface added or a cell given one), unique across
    // transports: what the gl back end has uploaded is current while it stays the same.
    std::uint64_t geometryRevision() const { return revision_; }
    // The cells a sweep visits (both back ends): the surface cells' bounds, `reach` cells wider,
    // within the grid; empty without surfaces.
    IndexBox sweepBox() const;
    // Per surface, nb shares (the first negative when the surface reflects by axis faces).
    std::vector<float> planeReflectionShares() const;
    std::array<std::vector<float>, kOrdinateFaces> faceReflectionShares() const;
    // Sources bin-major ([bin][surface][rgb]), as the sweeps read them.
    std::vector<float> binMajor(const Sources& sources) const;
    // Bins that share their axis, sign and lateral steps (one quadrant of a face) make every
    // move alike: the cpu sweeps up to kSweepLanes of them at once, one SIMD lane each.
    std::vector<std::vector<std::size_t>> sweepBundles() const;

private:
    int surfaceFor(glm::ivec3 cell);
    // A surface whose normals share one orientation (|m| at least 0.9 of its coverage) reflects
    // along its mean normal: that normal, else zero.
    glm::vec3 planeNormal(std::size_t s) const;
    void sweep(const std::vector<std::size_t>& bundle, const std::vector<float>& source, bool occlusion, const IndexBox& box,
               IrradianceBricks& irradiance, std::vector<glm::vec3>& reflected) const;
    // sweep with V a float per lane: one bin as a float, several as a SIMD vector (ordinates.cpp).
    template <class V>
    void sweepLanes(const std::vector<std::size_t>& bundle, const std::vector<float>& source, bool occlusion,
                    const IndexBox& box, IrradianceBricks& irradiance, std::vector<glm::vec3>& reflected) const;
    // Runs `add` (which adds bricks); new slots get no surfaces and a new geometry revision.
    template <typename Add>
    void allocate(Add add) {
        const std::size_t before = bricks_.slots();
        add();
        if (bricks_.slots() == before) return;
        surfaceOf_.resize(bricks_.slots() * std::size_t(shading::kBrickCells), -1);
        revision_ = newRevision();
    }
    static std::uint64_t newRevision();

    CascadeGrid grid_;
    std::vector<OrdinateBin> bins_;
    int reach_ = kSweepMargin;
    BrickMap bricks_;
    std::vector<int> surfaceOf_;  // per brick slot and cell: index into the surface arrays, -1 for none
    std::vector<glm::ivec3> cells_;
    IndexBox surfaceBounds_{glm::ivec3(1 << 30), glm::ivec3(-1)};  // of cells_; empty while there are none
    std::vector<float> coverage_;
    std::vector<glm::vec3> vectorCoverage_, albedo_;
    std::vector<glm::vec3> projected_;  // P
    std::uint64_t revision_ = 0;
    OrdinatesStats stats_;
};

template <typename Irradiance, typename Weight>
void OrdinatesTransport::addReflectedIrradiance(Irradiance irradiance, Weight weight, Sources& sources) {
    const float faceArea = grid_.cellSize * grid_.cellSize;
    std::vector<float> shares;
    for (std::size_t s = 0; s < coverage_.size(); ++s) {
        if (coverage_[s] <= 0.0f || albedo_[s] == glm::vec3(0.0f)) continue;
        const glm::vec3 p = grid_.cellCenter(cells_[s]);
        const float w = weight(p);
        if (w <= 0.0f) continue;
        const glm::vec3 m = vectorCoverage_[s], plane = planeNormal(s);
        if (plane != glm::vec3(0.0f)) {
            emissionShares(bins_, plane, shares);
            addFlux(p, plane, albedo_[s] * irradiance(p, plane) * (glm::length(m) * faceArea * w), shares.data(), 0.0f,
                    sources);
            continue;
        }
        for (int f = 0; f < kOrdinateFaces; ++f) {
            glm::vec3 n(0.0f);
            n[f / 2] = f % 2 == 0 ? 1.0f : -1.0f;
            const float part = std::max(m[f / 2] * n[f / 2], 0.0f);
            if (part <= 0.0f) continue;
            emissionShares(bins_, n, shares);
            addFlux(p, n, albedo_[s] * irradiance(p, n) * (part * faceArea * w), shares.data(), 0.0f, sources);
        }
    }
}

}  // namespace voxgi
