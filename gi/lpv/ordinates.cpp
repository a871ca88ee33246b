#include "gi/lpv/ordinates.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <stdexcept>

#include <tbb/parallel_for.h>

#include "gi/lpv/detail/subnormals_flushed.h"
#include "shaders/shared/ordinate_taps.h"
#include "volumes/blocker_sh.h"

namespace voxgi {

namespace {
// Bundles of bins are swept in this many groups, each summing into its own irradiance and
// reflections.
constexpr std::size_t kBinGroups = 4;
}  // namespace

std::vector<OrdinateBin> makeOrdinateBins(int perFace) {
    if (perFace < 2 || perFace % 2 != 0) throw std::invalid_argument("ordinate bins: perFace must be even and >= 2");
    // Midpoint rule over each bin's square of slopes; dw = ds dt / (1 + s^2 + t^2)^(3/2).
    constexpr int kSamples = 48;
    std::vector<OrdinateBin> bins;
    for (int axis = 0; axis < 3; ++axis)
        for (int sign : {1, -1})
            for (int j = 0; j < perFace; ++j)
                for (int i = 0; i < perFace; ++i) {
                    OrdinateBin b;
                    b.axis = axis;
                    b.sign = sign;
                    const float width = 2.0f / float(perFace);
                    const float s0 = -1.0f + width * float(i), t0 = -1.0f + width * float(j);
                    // Slopes of one sign per lateral axis: the second tap steps that way.
                    b.lateralStep = {s0 >= 0.0f ? 1 : -1, t0 >= 0.0f ? 1 : -1};
                    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
                    double taps[4] = {0, 0, 0, 0}, flux = 0.0, solid = 0.0;
                    glm::dvec3 moment(0.0);
                    for (int y = 0; y < kSamples; ++y)
                        for (int x = 0; x < kSamples; ++x) {
                            const double s = s0 + width * (x + 0.5) / kSamples, t = t0 + width * (y + 0.5) / kSamples;
                            const double r2 = 1.0 + s * s + t * t, r = std::sqrt(r2);
                            const double dw = (width / kSamples) * (width / kSamples) / (r2 * r);
                            glm::dvec3 w(0.0);
                            w[axis] = sign / r;
                            w[u] = s / r;
                            w[v] = t / r;
                            const double a = 1.0 / r;  // |w_axis|
                            solid += dw;
                            moment += w * dw;
                            flux += a * dw;
                            // A ray entering at a uniform lateral point moves |slope| cells over
                            // one slab: it lands one cell over with probability |slope|.
                            const double ps = std::abs(s), pt = std::abs(t), fw = a * dw;
                            taps[0] += (1 - ps) * (1 - pt) * fw;
                            taps[1] += ps * (1 - pt) * fw;
                            taps[2] += (1 - ps) * pt * fw;
                            taps[3] += ps * pt * fw;
                        }
                    for (int k = 0; k < 4; ++k) b.taps[std::size_t(k)] = float(taps[k] / flux);
                    b.moment = glm::vec3(moment);
                    b.solidAngle = float(solid);
                    b.axisFlux = float(flux);
                    bins.push_back(b);
                }
    return bins;
}

void emissionShares(const std::vector<OrdinateBin>& bins, glm::vec3 n, float* shares) {
    float sum = 0.0f;
    const bool isotropic = glm::dot(n, n) == 0.0f;
    for (std::size_t k = 0; k < bins.size(); ++k) {
        shares[k] = isotropic ? bins[k].solidAngle : std::max(glm::dot(n, bins[k].moment), 0.0f);
        sum += shares[k];
    }
    if (sum > 0.0f)
        for (std::size_t k = 0; k < bins.size(); ++k) shares[k] /= sum;
}

void emissionShares(const std::vector<OrdinateBin>& bins, glm::vec3 n, std::vector<float>& shares) {
    shares.resize(bins.size());
    emissionShares(bins, n, shares.data());
}

namespace {
// Revisions are unique across transports: a new transport never looks like an uploaded one.
std::atomic<std::uint64_t> nextRevision{1};
}  // namespace

std::uint64_t OrdinatesTransport::newRevision() { return nextRevision++; }

int ordinatesReach(float applyNormalOffsetCells) {
    return std::max(kSweepMargin, int(std::ceil(std::max(applyNormalOffsetCells, 0.0f))) + 1);
}

OrdinatesTransport::OrdinatesTransport(const CascadeGrid& grid, int perFace, int reach)
    : grid_(grid),
      bins_(makeOrdinateBins(perFace)),
      reach_(reach),
      bricks_(grid.resolution),
      revision_(newRevision()) {}

void OrdinatesTransport::allocateAllBricks() {
    allocate([&] { bricks_.allocateAll(); });
}

glm::vec4 OrdinatesTransport::irradianceAt(const IrradianceBricks& e, glm::ivec3 cell, int face) const {
    const int slot = bricks_.slotOf(cell);
    if (slot < 0) return glm::vec4(0.0f);
    const std::size_t i = std::size_t(shading::brickValue(int(bricks_.slots()), shading::brickCell(slot, cell), face));
    return i < e.size() ? e[i] : glm::vec4(0.0f);
}

glm::vec3 OrdinatesTransport::planeNormal(std::size_t s) const {
    const glm::vec3 m = vectorCoverage_[s];
    const float lm = glm::length(m);
    return lm > 0.0f && lm >= 0.9f * coverage_[s] ? m / lm : glm::vec3(0.0f);
}

int OrdinatesTransport::surfaceIndex(glm::ivec3 cell) const {
    const int slot = bricks_.slotOf(cell);
    return slot < 0 ? -1 : surfaceOf_[BrickMap::brickCell(slot, cell)];
}

int OrdinatesTransport::surfaceFor(glm::ivec3 cell) {
    if (const int known = surfaceIndex(cell); known >= 0) return known;
    // A surface cell stores light `reach_` cells around it: its receivers read there.
    allocate([&] { bricks_.allocateAround(cell, reach_); });
    const int s = int(cells_.size());
    surfaceOf_[BrickMap::brickCell(bricks_.slotOf(cell), cell)] = s;
    revision_ = newRevision();
    cells_.push_back(cell);
    surfaceBounds_.min = glm::min(surfaceBounds_.min, cell);
    surfaceBounds_.max = glm::max(surfaceBounds_.max, cell);
    coverage_.push_back(0.0f);
    vectorCoverage_.push_back(glm::vec3(0.0f));
    albedo_.push_back(glm::vec3(0.0f));
    projected_.push_back(glm::vec3(0.0f));
    return s;
}

void OrdinatesTransport::addSurface(const OrdinateSurface& surface) {
    if (!grid_.contains(surface.cell) || surface.coverage <= 0.0f) return;
    const int s = surfaceFor(surface.cell);
    const float total = coverage_[std::size_t(s)] + surface.coverage;
    albedo_[std::size_t(s)] =
        (albedo_[std::size_t(s)] * coverage_[std::size_t(s)] + surface.albedo * surface.coverage) / total;
    coverage_[std::size_t(s)] = total;
    vectorCoverage_[std::size_t(s)] += surface.vectorCoverage;
    projected_[std::size_t(s)] += surface.projectedCoverage != glm::vec3(0.0f)
                                      ? surface.projectedCoverage
                                      : isotropicProjectedCoverage(surface.coverage, surface.vectorCoverage);
    revision_ = newRevision();
}

void OrdinatesTransport::addSurfaces(const std::vector<OrdinateSurface>& surfaces) {
    std::vector<glm::ivec3> cells;
    cells.reserve(surfaces.size());
    for (const OrdinateSurface& s : surfaces)
        if (grid_.contains(s.cell) && s.coverage > 0.0f) cells.push_back(s.cell);
    allocate([&] { bricks_.allocateAround(cells, reach_); });
    for (const OrdinateSurface& s : surfaces) addSurface(s);
}

OrdinatesTransport::Sources OrdinatesTransport::emptySources() const {
    Sources s;
    s.power.assign(coverage_.size() * bins_.size() * 3, 0.0f);
    return s;
}

void OrdinatesTransport::addFlux(glm::vec3 position, glm::vec3 normal, glm::vec3 flux, const float* shares,
                                 float normalOffsetCells, Sources& sources) {
    const glm::ivec3 cell = grid_.cellOf(position + normal * (normalOffsetCells * grid_.cellSize));
    if (!grid_.contains(cell)) {
        sources.outsideWatts += double(flux.r + flux.g + flux.b);
        return;
    }
    const std::size_t surface = std::size_t(surfaceFor(cell)), nb = bins_.size();
    if (sources.power.size() < coverage_.size() * nb * 3) sources.power.resize(coverage_.size() * nb * 3, 0.0f);
    float* p = sources.power.data() + surface * nb * 3;
    for (std::size_t k = 0; k < nb; ++k) {
        if (shares[k] == 0.0f) continue;
        p[3 * k] += flux.r * shares[k];
        p[3 * k + 1] += flux.g * shares[k];
        p[3 * k + 2] += flux.b * shares[k];
    }
    sources.watts += double(flux.r + flux.g + flux.b);
}

void OrdinatesTransport::addSurfels(const SurfelSource& source, float normalOffsetCells, Sources& sources) {
    std::vector<float> shares;
    for (const Surfel& s : source.surfels) {
        if (s.flux == glm::vec3(0.0f)) continue;
        emissionShares(bins_, s.normal, shares);
        addFlux(s.position, s.normal, s.flux, shares.data(), normalOffsetCells, sources);
    }
}

namespace {
// One value per lane (bin) of a bundle: a SIMD vector (GCC's and Clang's vector extension), or
// a plain float for bundles of one bin (lpv's 24 bins: one per quadrant of a face), where four
// lanes would carry three of zeros through the slab buffers.
typedef float Lanes __attribute__((vector_size(sizeof(float) * kSweepLanes)));
template <class V>
constexpr std::size_t kWidth = sizeof(V) / sizeof(float);
float& lane(float& v, std::size_t) { return v; }
float lane(const float& v, std::size_t) { return v; }
float& lane(Lanes& v, std::size_t l) { return reinterpret_cast<float*>(&v)[l]; }
float lane(const Lanes& v, std::size_t l) { return v[l]; }

// One colour triple per lane, colour-major: each colour is one vector.
template <class V>
struct LaneRgb {
    V c[3] = {};

    bool any() const {
        for (std::size_t l = 0; l < kWidth<V>; ++l)
            if (lane(c[0], l) != 0.0f || lane(c[1], l) != 0.0f || lane(c[2], l) != 0.0f) return true;
        return false;
    }
    // Summed over the lanes: what every bin together leaves in a cell.
    glm::vec3 total() const {
        glm::vec3 t(0.0f);
        for (int k = 0; k < 3; ++k)
            for (std::size_t l = 0; l < kWidth<V>; ++l) t[k] += lane(c[k], l);
        return t;
    }
    LaneRgb& operator+=(const LaneRgb& o) {
        for (int k = 0; k < 3; ++k) c[k] += o.c[k];
        return *this;
    }
    LaneRgb& operator-=(const LaneRgb& o) {
        for (int k = 0; k < 3; ++k) c[k] -= o.c[k];
        return *this;
    }
    LaneRgb& operator*=(float s) {
        for (int k = 0; k < 3; ++k) c[k] *= s;
        return *this;
    }
    LaneRgb operator*(float s) const { return LaneRgb(*this) *= s; }
    // Each lane times its own factor (a tap's weight in that lane's bin).
    LaneRgb perLane(V s) const {
        LaneRgb r;
        for (int k = 0; k < 3; ++k) r.c[k] = c[k] * s;
        return r;
    }
};
}  // namespace

std::vector<std::vector<std::size_t>> OrdinatesTransport::sweepBundles() const {
    std::vector<std::vector<std::size_t>> bundles;
    for (std::size_t k = 0; k < bins_.size(); ++k) {
        const OrdinateBin& b = bins_[k];
        auto alike = std::find_if(bundles.begin(), bundles.end(), [&](const std::vector<std::size_t>& bundle) {
            const OrdinateBin& o = bins_[bundle.front()];
            return bundle.size() < kSweepLanes && o.axis == b.axis && o.sign == b.sign && o.lateralStep == b.lateralStep;
        });
        if (alike == bundles.end())
            bundles.push_back({k});
        else
            alike->push_back(k);
    }
    return bundles;
}

// The bins of one bundle over `box` (the cells that can hold light a receiver reads: sweepBox):
// slab by slab along their axis, each slab's incoming power from the previous slab's outgoing
// power through the four landing taps. The bins share every move and every surface's stopping
// fraction; only the taps' weights and the sources differ, lane by lane.
void OrdinatesTransport::sweep(const std::vector<std::size_t>& bundle, const std::vector<float>& source, bool occlusion,
                               const IndexBox& box, IrradianceBricks& irradiance, std::vector<glm::vec3>& reflected) const {
    if (bundle.size() == 1)
        sweepLanes<float>(bundle, source, occlusion, box, irradiance, reflected);
    else
        sweepLanes<Lanes>(bundle, source, occlusion, box, irradiance, reflected);
}

template <class V>
void OrdinatesTransport::sweepLanes(const std::vector<std::size_t>& bundle, const std::vector<float>& source,
                                    bool occlusion, const IndexBox& box, IrradianceBricks& irradiance,
                                    std::vector<glm::vec3>& reflected) const {
    const OrdinateBin& b = bins_[bundle.front()];
    const int n = grid_.resolution;
    const int axis = b.axis, u = (axis + 1) % 3, v = (axis + 2) % 3;
    const int su = b.lateralStep.x, sv = b.lateralStep.y;
    // Per tap, each lane's weight (zero in unused lanes: they carry nothing).
    V taps[4] = {};
    const std::size_t lanes = std::min(bundle.size(), kWidth<V>);
    const float* laneSources[kSweepLanes] = {};  // each lane's bin's sources, per surface
    for (std::size_t l = 0; l < lanes; ++l) {
        for (int j = 0; j < 4; ++j) lane(taps[j], l) = bins_[bundle[l]].taps[std::size_t(j)];
        laneSources[l] = source.data() + bundle[l] * coverage_.size() * 3;
    }
    // Receivers: the power entering a cell through its faces of axis a, over h^2, is the
    // irradiance on a surface facing against the move (moving along +e_a, light arrives on faces
    // facing -e_a: face 2a + 1). In free space this equals radiance x the bin's cosine moment; in a
    // cell whose surfaces stop the light it counts only what crosses into it, as a surface there
    // receives it.
    const float perArea = 1.0f / (grid_.cellSize * grid_.cellSize);
    const std::size_t faceStride = bricks_.faceStride();
    const std::size_t slabFace = std::size_t(2 * axis + (b.sign > 0 ? 1 : 0)) * faceStride,
                      uFace = std::size_t(2 * u + (su > 0 ? 1 : 0)) * faceStride,
                      vFace = std::size_t(2 * v + (sv > 0 ? 1 : 0)) * faceStride;
    // Per lateral cell of the previous slab, the power leaving along each tap.
    // A border of zeros around each slab: taps that reach past the edge read nothing.
    using Parts = std::array<LaneRgb<V>, 4>;
    const std::size_t row = std::size_t(n) + 2;
    std::vector<Parts> prev(row * row, Parts{}), cur(prev.size(), Parts{});
    // The taps' moves, in world axes: each crosses the slab face and, for taps 1-3, a side face.
    const int axes[3] = {axis, u, v};
    glm::vec3 move[4];
    for (int j = 0; j < 4; ++j) {
        move[j] = glm::vec3(0.0f);
        move[j][axis] = float(b.sign);
        if (j & 1) move[j][u] = float(su);
        if (j & 2) move[j][v] = float(sv);
    }
    auto crossedBy = [&](int j, glm::vec3 perAxis) { return shading::crossedBy(j, perAxis, axis, u, v); };
    // Reflects `hit` (stopped by the surfaces of `s` on tap j's move, summed over the lanes) from
    // the axis faces the light arrives on, each crossed axis by its part of the stopping area
    // `parts`. With `cell`, the stopped light is also irradiance on those faces there: light that
    // moved inside the cell (along a floor's layer, or from another surface of the cell) before
    // meeting a surface, which no crossing into the cell counted.
    auto reflect = [&](int s, int j, glm::vec3 hit, const glm::vec3& parts, std::size_t cell = SIZE_MAX) {  // cell: brickCell
        const float total = parts.x + parts.y + parts.z;
        const glm::vec3 r = albedo_[std::size_t(s)] * hit;
        for (int c = 0; c < 3; ++c) {
            const float share = total > 0.0f ? parts[c] / total : (c == 0 ? 1.0f : 0.0f);
            if (share <= 0.0f) continue;
            const int ax = axes[c];
            // Moving along +a, light meets the face facing -a (face 2a + 1).
            const std::size_t face = std::size_t(2 * ax + (move[j][ax] > 0.0f ? 1 : 0));
            reflected[kOrdinateFaces * std::size_t(s) + face] += r * share;
            if (cell != SIZE_MAX) irradiance[cell + face * faceStride] += glm::vec4(hit * (share * perArea), 0.0f);
        }
    };
    // The inner loop runs along x where it is lateral (contiguous in a brick, and a row of bricks
    // is a run of slots: BrickMap::allocateAround), else along y.
    const int innerAxis = u == 0 || v == 0 ? 0 : 1;
    const bool uInner = innerAxis == u;
    const int outerAxis = uInner ? v : u;
    // Slab offsets of the taps' upstream cells (the slab buffers run along the inner axis).
    const std::ptrdiff_t du = uInner ? su : std::ptrdiff_t(su) * std::ptrdiff_t(row),
                         dv = uInner ? std::ptrdiff_t(sv) * std::ptrdiff_t(row) : sv;
    const std::ptrdiff_t from[4] = {0, -du, -dv, -du - dv};
    // A cell's offset in its brick and its brick's table index, axis by axis (light_bricks.h:
    // bits 0, 3 and 6 of the offset for x, y and z; the table's x fastest too).
    const int side = bricks_.tableSide();
    const int shift[3] = {0, 3, 6}, tableStride[3] = {1, side, side * side};
    const int innerShift = shift[innerAxis], innerTable = tableStride[innerAxis];
    const int* table = bricks_.table().data();
    const int lo = box.min[innerAxis], hi = box.max[innerAxis];
    const int first = box.min[axis], last = box.max[axis];
    for (int t = 0; t <= last - first; ++t) {
        const int a = b.sign > 0 ? first + t : last - t;
        const int slabOffset = (a & 7) << shift[axis], slabTable = (a >> 3) * tableStride[axis];
        for (int outer = box.min[outerAxis]; outer <= box.max[outerAxis]; ++outer) {
            const int rowOffset = slabOffset | ((outer & 7) << shift[outerAxis]),
                      rowTable = slabTable + (outer >> 3) * tableStride[outerAxis];
            // The row brick by brick: each run of cells in one brick looks its slot up once.
            for (int run = lo; run <= hi; run = (run | 7) + 1) {
                const int runEnd = std::min(run | 7, hi);
                const int slot = table[rowTable + (run >> 3) * innerTable];
                const std::size_t runBase =
                    slot < 0 ? 0 : std::size_t(slot) * std::size_t(shading::kBrickCells) + std::size_t(rowOffset);
                for (int inner = run; inner <= runEnd; ++inner) {
                    const std::size_t here = (std::size_t(outer) + 1) * row + std::size_t(inner) + 1;
                    LaneRgb<V> part[4];
                    for (int j = 0; j < 4; ++j) part[j] = prev[std::size_t(std::ptrdiff_t(here) + from[j])][std::size_t(j)];
                    LaneRgb<V> out = part[0];
                    out += part[1];
                    out += part[2];
                    out += part[3];
                    // Outside the bricks no receiver reads and no surface is: the light only moves on.
                    const std::size_t brickCell = runBase + (std::size_t(inner & 7) << innerShift);
                    const std::size_t cell = slot < 0 ? SIZE_MAX : brickCell;
                    const bool lit = out.any();
                    if (lit && slot >= 0) {
                        irradiance[cell + slabFace] += glm::vec4(out.total() * perArea, 0.0f);
                        irradiance[cell + uFace] += glm::vec4((part[1].total() + part[3].total()) * perArea, 0.0f);
                        irradiance[cell + vFace] += glm::vec4((part[2].total() + part[3].total()) * perArea, 0.0f);
                    }
                    Parts& leaving = cur[here];
                    const int s = slot < 0 ? -1 : surfaceOf_[brickCell];
                    if (s < 0) {
                        for (int j = 0; j < 4; ++j) leaving[std::size_t(j)] = out.perLane(taps[j]);
                        continue;
                    }
                    const glm::vec3 m = vectorCoverage_[std::size_t(s)];
                    if (occlusion && lit) {
                        // Entering a cell, a move meets the surfaces whose normal axis it crosses, from
                        // either side: a floor stops what moves up or down into its cell, not what
                        // slides along it.
                        const glm::vec3 shadow = clutterShadow(std::size_t(s));
                        for (int j = 0; j < 4; ++j) {
                            if (!part[j].any()) continue;
                            const glm::vec3 crossed = shading::enteringStop(j, glm::abs(m), shadow, axis, u, v);
                            const float stopped = std::min(crossed.x + crossed.y + crossed.z, 1.0f);
                            if (stopped <= 0.0f) continue;
                            const LaneRgb<V> hit = part[j] * stopped;
                            out -= hit;
                            reflect(s, j, hit.total(), crossed);
                        }
                    }
                    for (std::size_t l = 0; l < lanes; ++l) {
                        const float* p = laneSources[l] + std::size_t(s) * 3;
                        for (int c = 0; c < 3; ++c) lane(out.c[c], l) += p[c];
                    }
                    for (int j = 0; j < 4; ++j) {
                        LaneRgb<V> go = out.perLane(taps[j]);
                        if (occlusion && go.any()) {
                            // Leaving a cell, a move meets the surfaces there that face against it (a
                            // corner cell's wall, for the light its floor reflects towards the wall).
                            const glm::vec3 facing = crossedBy(j, glm::max(-m * move[j], glm::vec3(0.0f)));
                            const float stopped = std::min(facing.x + facing.y + facing.z, 1.0f);
                            if (stopped > 0.0f) {
                                reflect(s, j, go.total() * stopped, facing, cell);
                                go *= 1.0f - stopped;
                            }
                        }
                        leaving[std::size_t(j)] = go;
                    }
                }
            }
        }
        std::swap(prev, cur);
    }
}

// Light starts at surface cells (sources sit in them) and only surfaces stop it, so light leaving
// the bounding box of the surface cells never returns, and outside it no receiver reads it but
// within the apply pass's reach (its normal offset and trilinear taps: kSweepMargin cells).
IndexBox OrdinatesTransport::sweepBox() const {
    IndexBox box = surfaceBounds_;
    if (box.empty()) return box;
    box.min = glm::max(box.min - reach_, glm::ivec3(0));
    box.max = glm::min(box.max + reach_, glm::ivec3(grid_.resolution - 1));
    return box;
}

std::array<std::vector<float>, kOrdinateFaces> OrdinatesTransport::faceReflectionShares() const {
    std::array<std::vector<float>, kOrdinateFaces> shares;
    for (int f = 0; f < kOrdinateFaces; ++f) {
        glm::vec3 n(0.0f);
        n[f / 2] = f % 2 == 0 ? 1.0f : -1.0f;
        emissionShares(bins_, n, shares[std::size_t(f)]);
    }
    return shares;
}

// A cell whose surfaces share one orientation reflects along its mean normal: a slanted wall or a
// vault sends its light where it faces, not into axis hemispheres.
std::vector<float> OrdinatesTransport::planeReflectionShares() const {
    const std::size_t nb = bins_.size();
    std::vector<float> shares(coverage_.size() * nb, -1.0f);
    for (std::size_t s = 0; s < coverage_.size(); ++s)
        if (const glm::vec3 n = planeNormal(s); n != glm::vec3(0.0f)) emissionShares(bins_, n, shares.data() + s * nb);
    return shares;
}

// The sweeps read the sources bin by bin: bin-major ([bin][surface][rgb]), where surface-major
// lookups were a cache miss per surface cell.
std::vector<float> OrdinatesTransport::binMajor(const Sources& sources) const {
    const std::size_t surfaces = coverage_.size(), nb = bins_.size();
    std::vector<float> out(surfaces * nb * 3, 0.0f);
    for (std::size_t s = 0; s < surfaces && (s + 1) * nb * 3 <= sources.power.size(); ++s)
        for (std::size_t k = 0; k < nb; ++k)
            for (std::size_t c = 0; c < 3; ++c) out[(k * surfaces + s) * 3 + c] = sources.power[(s * nb + k) * 3 + c];
    return out;
}

IrradianceBricks OrdinatesTransport::solve(const Sources& sources, bool occlusion, int maxBounces,
                                           std::vector<glm::vec3>* carry) {
    stats_ = {};
    stats_.emittedWatts = sources.watts;
    const std::size_t values = bricks_.valueCount(), surfaces = coverage_.size(), nb = bins_.size();
    IrradianceBricks irradiance(values, glm::vec4(0.0f));
    const std::array<std::vector<float>, kOrdinateFaces> faceShares = faceReflectionShares();
    const std::vector<float> planeShares = planeReflectionShares();
    auto reflectionSources = [&](const std::vector<glm::vec3>& reflected, std::vector<float>& out) {
        double watts = 0.0;
        for (std::size_t s = 0; s < surfaces; ++s) {
            const glm::vec3* r = reflected.data() + kOrdinateFaces * s;
            for (int f = 0; f < kOrdinateFaces; ++f) watts += double(r[f].r + r[f].g + r[f].b);
            if (planeShares[s * nb] >= 0.0f) {
                glm::vec3 total(0.0f);
                for (int f = 0; f < kOrdinateFaces; ++f) total += r[f];
                for (std::size_t k = 0; k < nb; ++k) {
                    float* q = out.data() + (k * surfaces + s) * 3;
                    const float w = planeShares[s * nb + k];
                    q[0] += total.r * w;
                    q[1] += total.g * w;
                    q[2] += total.b * w;
                }
                continue;
            }
            for (std::size_t k = 0; k < nb; ++k) {
                glm::vec3 p(0.0f);
                for (std::size_t f = 0; f < std::size_t(kOrdinateFaces); ++f) p += r[f] * faceShares[f][k];
                float* q = out.data() + (k * surfaces + s) * 3;
                q[0] += p.r;
                q[1] += p.g;
                q[2] += p.b;
            }
        }
        return watts;
    };
    const IndexBox box = sweepBox();
    std::vector<float> source = binMajor(sources);
    double carried = sources.watts;
    // The reflections an earlier solve left to carry start this one's bounces.
    if (carry && carry->size() == kOrdinateFaces * surfaces) carried += reflectionSources(*carry, source);
    // Bundles in a fixed number of groups, each summing into its own buffers, added in group
    // order: the same image whichever thread sweeps which bundle.
    struct Local {
        IrradianceBricks irradiance;
        std::vector<glm::vec3> reflected;
    };
    const std::vector<std::vector<std::size_t>> bundles = sweepBundles();
    const std::size_t groups = std::min<std::size_t>(bundles.size(), kBinGroups);
    std::vector<Local> locals(groups);
    std::vector<glm::vec3> reflected(kOrdinateFaces * surfaces, glm::vec3(0.0f));
    for (int bounce = 0; bounce < maxBounces && carried > 0.0 && !box.empty(); ++bounce) {
        // Each group's irradiance sums over every sweep; its reflections start anew each sweep.
        tbb::parallel_for(std::size_t(0), groups, [&](std::size_t g) {
            Local& l = locals[g];
            if (l.reflected.empty()) {
                l.irradiance.assign(values, glm::vec4(0.0f));
                l.reflected.assign(kOrdinateFaces * surfaces, glm::vec3(0.0f));
            } else {
                std::fill(l.reflected.begin(), l.reflected.end(), glm::vec3(0.0f));
            }
            const detail::SubnormalsFlushed flushed;
            for (std::size_t k = g; k < bundles.size(); k += groups) sweep(bundles[k], source, occlusion, box, l.irradiance, l.reflected);
        });
        std::fill(reflected.begin(), reflected.end(), glm::vec3(0.0f));
        for (const Local& l : locals)
            for (std::size_t i = 0; i < l.reflected.size(); ++i) reflected[i] += l.reflected[i];
        ++stats_.sweeps;
        // The next sweep's sources: each face's reflection into its hemisphere's bins.
        std::fill(source.begin(), source.end(), 0.0f);
        carried = reflectionSources(reflected, source);
        stats_.reflectedWatts += carried;
        stats_.leftWatts = carried;
        if (carried < kOrdinatesConverged * sources.watts) break;
    }
    if (carry) *carry = reflected;
    for (const Local& l : locals) {
        if (l.reflected.empty()) continue;
        for (std::size_t i = 0; i < values; ++i) irradiance[i] += l.irradiance[i];
    }
    return irradiance;
}

}  // namespace voxgi
