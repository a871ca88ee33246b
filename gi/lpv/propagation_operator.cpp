// Building the CPU propagator's transfer operator from a cascade's geometry volume, and the
// conversions between LightVolume and the structure-of-arrays layout the steps run on.
#include <algorithm>
#include <cstring>

#include <tbb/parallel_for.h>

#include "gi/lpv/detail/propagation_soa.h"
#include "gi/sh/sh.h"
#include "shaders/shared/constants.h"

namespace voxgi::lpv_detail {

SoaLayout::SoaLayout(int resolution)
    : n(resolution), runsX((resolution + kLanes - 1) / kLanes), rowRuns(std::size_t(runsX) + 2),
      sy(std::size_t(resolution) + 2), rowStride(rowRuns * kRunFloats), size(rowStride * sy * sy) {}

void SoaLight::reset(const SoaLayout& l) {
    layout = l;
    data.assign(l.size, 0.0f);
}

void SoaLight::fromVolume(const LightVolume& v) {
    const int n = layout.n;
    const std::vector<glm::vec4>* colours[3] = {&v.r, &v.g, &v.b};
    tbb::parallel_for(0, n, [&](int z) {
        for (int y = 0; y < n; ++y) {
            const std::size_t from = v.grid.index({0, y, z});
            for (int x = 0; x < n; ++x)
                for (int c = 0; c < 3; ++c)
                    for (int k = 0; k < 4; ++k) data[layout.cell(x, y, z, c * 4 + k)] = (*colours[c])[from + std::size_t(x)][k];
        }
    });
}

void SoaLight::toVolume(LightVolume& v) const {
    const int n = layout.n;
    std::vector<glm::vec4>* colours[3] = {&v.r, &v.g, &v.b};
    tbb::parallel_for(0, n, [&](int z) {
        for (int y = 0; y < n; ++y) {
            const std::size_t to = v.grid.index({0, y, z});
            for (int x = 0; x < n; ++x)
                for (int c = 0; c < 3; ++c)
                    for (int k = 0; k < 4; ++k) (*colours[c])[to + std::size_t(x)][k] = data[layout.cell(x, y, z, c * 4 + k)];
        }
    });
}

namespace {

float clamp01(float x) { return x < 0.0f ? 0.0f : (x > 1.0f ? 1.0f : x); }

// The reflected light's lobe: the blocker's SH with unit flux, its band-1 part limited to
// that of a clamped cosine (|c1| <= 2/sqrt(3) c0). Blockers fitted or merged from several
// surfaces can have a stronger band 1, and such a lobe, re-emitted step after step, would let
// the directional terms grow without bound while the flux stays put.
glm::vec4 reflectionShape(glm::vec4 blocker, float flux) {
    glm::vec4 shape = blocker / flux;
    glm::vec3 band1(shape.y, shape.z, shape.w);
    float limit = 1.1547005f * shape.x, length = glm::length(band1);
    if (length > limit) band1 *= limit / length;
    return glm::vec4(shape.x, band1);
}

// What the steps need from the geometry at one face of the grid, for light crossing it in
// each direction along its axis (0: toward +k, 1: toward -k): the fractions beta_f of the flux
// stopped on its way to each of the 5 faces beyond, the SH whose dot with the sending cell's
// light gives the total flux stopped (for bounces), and the reflected lobe and albedo.
struct FaceRecord {
    float beta[2][5];
    glm::vec4 blocked[2];
    glm::vec4 shape;   // unit-flux reflection lobe
    glm::vec3 albedo;
    bool reflects;     // has flux and a non-black albedo
};

// For each axis k, the face on the low-k side of cell c (c_k in [0, n]) samples the geometry
// volume at its centre: the mean of its 4 corner samples (one trilinear fetch on the GPU).
class FaceTable {
public:
    FaceTable(const BlockerVolume& gv, bool bounces) : n_(gv.grid.resolution) {
        const PropagationKernel& kernel = propagationKernel();
        const std::size_t count = std::size_t(n_ + 1) * std::size_t(n_ + 1) * std::size_t(n_ + 1);
        std::vector<std::vector<FaceRecord>> slices(std::size_t(n_ + 1));
        for (int k = 0; k < 3; ++k) index_[k].assign(count, -1);
        // Corners holding a blocker: most faces of a cascade have none and are skipped on these.
        std::vector<std::uint8_t> blocks(count);
        tbb::parallel_for(std::size_t(0), count, [&](std::size_t i) { blocks[i] = gv.blocker[i] != glm::vec4(0.0f); });
        // Faces share the corner grid's indexing (face on the low-k side of cell c = corner c).
        const std::size_t N = std::size_t(n_ + 1), stride[3] = {1, N, N * N};
        tbb::parallel_for(0, n_ + 1, [&](int z) {
            auto& local = slices[std::size_t(z)];
            for (int y = 0; y <= n_; ++y)
                for (int x = 0; x <= n_; ++x) {
                    const glm::ivec3 c(x, y, z);
                    const std::size_t i = indexOf(c);
                    for (int k = 0; k < 3; ++k) {
                        const int u = (k + 1) % 3, v = (k + 2) % 3;
                        if (c[u] == n_ || c[v] == n_) continue;  // not a face of the grid
                        const std::size_t su = stride[u], sv = stride[v];
                        if (!(blocks[i] | blocks[i + sv] | blocks[i + su] | blocks[i + su + sv])) continue;
                        glm::vec4 b = gv.blocker[i] + gv.blocker[i + sv] + gv.blocker[i + su] + gv.blocker[i + su + sv];
                        const glm::vec3 a = gv.albedo[i] + gv.albedo[i + sv] + gv.albedo[i + su] + gv.albedo[i + su + sv];
                        if (b == glm::vec4(0.0f)) continue;
                        b *= 0.25f;
                        FaceRecord r{};
                        for (int dir = 0; dir < 2; ++dir) {
                            const auto& faces = kernel.faces[std::size_t(2 * k + dir)];
                            for (int f = 0; f < 5; ++f) {
                                r.beta[dir][f] = clamp01(glm::dot(b, faces[std::size_t(f)].block));
                                r.blocked[dir] += r.beta[dir][f] * faces[std::size_t(f)].sample;
                            }
                        }
                        r.albedo = 0.25f * a;
                        const float flux = b.x * (4.0f * shading::kPi * sh::kY00);
                        r.reflects = bounces && flux > 1e-12f && r.albedo != glm::vec3(0.0f);
                        if (r.reflects) r.shape = reflectionShape(b, flux);
                        index_[k][i] = std::int32_t(local.size());
                        local.push_back(r);
                    }
                }
        });
        // Index entries stay slice-local: a face's slice is its z, known at every lookup.
        records_ = std::move(slices);
    }

    // The faces between `cell` and its neighbour at -e_k (low) or +e_k (high), or null where
    // nothing blocks.
    const FaceRecord* lowSide(glm::ivec3 cell, int k) const { return record(index_[k][indexOf(cell)], cell.z); }
    const FaceRecord* highSide(glm::ivec3 cell, int k) const {
        cell[k] += 1;
        return record(index_[k][indexOf(cell)], cell.z);
    }

private:
    std::size_t indexOf(glm::ivec3 c) const {
        return (std::size_t(c.z) * std::size_t(n_ + 1) + std::size_t(c.y)) * std::size_t(n_ + 1) + std::size_t(c.x);
    }
    const FaceRecord* record(std::int32_t i, int z) const {
        return i < 0 ? nullptr : &records_[std::size_t(z)][std::size_t(i)];
    }
    int n_;
    std::vector<std::int32_t> index_[3];
    std::vector<std::vector<FaceRecord>> records_;  // per slice z
};

}  // namespace

PropagationOperator::PropagationOperator(const BlockerVolume& gv, const CascadeGrid& grid,
                                         const PropagationOptions& opt)
    : layout(grid.resolution) {
    pass.assign(layout.runCount() * 6, nullptr);
    bounce.assign(layout.runCount(), nullptr);
    if (!opt.occlusion || gv.blocker.empty()) return;
    const FaceTable faces(gv, opt.bounces);
    const int n = grid.resolution;
    // Rows of runs are built in parallel into their own pools; pointers are taken once a row's
    // pool is complete.
    passRows_.resize(std::size_t(n) * std::size_t(n));
    bounceRows_.resize(passRows_.size());
    tbb::parallel_for(0, n * n, [&](int yz) {
        const int y = yz % n, z = yz / n;
        auto& passLocal = passRows_[std::size_t(yz)];
        auto& bounceLocal = bounceRows_[std::size_t(yz)];
        std::vector<std::pair<std::size_t, std::size_t>> passAt, bounceAt;  // (slot, offset)
        for (int rx = 0; rx < layout.runsX; ++rx) {
            const std::size_t run = layout.run(rx, y, z);
            const FaceRecord* gatherFace[6][kLanes] = {};
            glm::vec4 matrices[kLanes][3][4];  // [lane][colour][column]
            bool anyOccluded[6] = {false, false, false, false, false, false}, anyBounce = false;
            bool bounces[kLanes] = {};
            for (int lane = 0; lane < kLanes; ++lane) {
                const int x = rx * kLanes + lane;
                if (x >= n) break;
                const glm::ivec3 d(x, y, z);
                for (int k = 0; k < 3; ++k) {
                    // The faces on the cell's low-k and high-k sides.
                    const FaceRecord* low = faces.lowSide(d, k);
                    const FaceRecord* high = faces.highSide(d, k);
                    // Light arriving along +k crosses the low face, along -k the high face.
                    gatherFace[2 * k][lane] = low;
                    gatherFace[2 * k + 1][lane] = high;
                    anyOccluded[2 * k] |= low != nullptr;
                    anyOccluded[2 * k + 1] |= high != nullptr;
                    // This cell's light stopped at its face toward +k (the high face) or -k (the
                    // low face) bounces back into it, shaped like the blocker's lobe with unit flux.
                    for (int dir = 0; dir < 2; ++dir) {
                        const FaceRecord* r = dir == 0 ? high : low;
                        if (!r || !r->reflects) continue;
                        if (!bounces[lane])
                            for (auto& colour : matrices[lane])
                                for (auto& column : colour) column = glm::vec4(0.0f);
                        bounces[lane] = anyBounce = true;
                        for (int c = 0; c < 3; ++c)
                            for (int col = 0; col < 4; ++col)
                                matrices[lane][c][col] += (r->albedo[c] * r->blocked[dir][col]) * r->shape;
                    }
                }
            }
            for (int a = 0; a < 6; ++a) {
                if (!anyOccluded[a]) continue;
                const std::size_t at = passLocal.size();
                passAt.emplace_back(run * 6 + std::size_t(a), at);
                passLocal.resize(at + 5 * kLanes, 0.0f);
                for (int lane = 0; lane < kLanes; ++lane)
                    for (int f = 0; f < 5; ++f)
                        passLocal[at + f * kLanes + lane] = gatherFace[a][lane] ? 1.0f - gatherFace[a][lane]->beta[a % 2][f] : 1.0f;
            }
            if (!anyBounce) continue;
            const std::size_t at = bounceLocal.size();
            bounceAt.emplace_back(run, at);
            bounceLocal.resize(at + kBounceFloats, 0.0f);
            for (int lane = 0; lane < kLanes; ++lane) {
                if (!bounces[lane]) continue;
                for (int c = 0; c < 3; ++c)
                    for (int col = 0; col < 4; ++col)
                        for (int row = 0; row < 4; ++row)
                            bounceLocal[at + std::size_t(((c * 4 + col) * 4 + row) * kLanes + lane)] = matrices[lane][c][col][row];
            }
        }
        for (const auto& [slot, offset] : passAt) pass[slot] = passLocal.data() + offset;
        for (const auto& [slot, offset] : bounceAt) bounce[slot] = bounceLocal.data() + offset;
    });
    for (std::size_t run = 0; run < bounce.size(); ++run) {
        occludedRuns += std::any_of(pass.begin() + std::ptrdiff_t(run * 6), pass.begin() + std::ptrdiff_t(run * 6 + 6),
                                    [](const float* p) { return p != nullptr; })
                            ? 1
                            : 0;
        bounceRuns += bounce[run] != nullptr ? 1 : 0;
    }
}

}  // namespace voxgi::lpv_detail
