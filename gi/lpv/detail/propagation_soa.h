// The CPU propagator's working form (internal to gi/lpv): light in structure-of-arrays layout
// and the transfer operator stored per run of 8 cells along x, so one SIMD lane is one cell.
//
// Why this shape: with one 4x4 matrix per occluded (cell, neighbour) and one cell at a time,
// the steps streamed 64 B per occluded face and ran memory-bound on Sibenik and Sponza. The
// transfer through a face is rank one (flux = pass * sample . I, re-emitted as a fixed lobe),
// so an occluded neighbour needs only its 5 pass factors (20 B); open neighbours use the axis's
// unoccluded matrix (6 non-zeros, from the symmetry of the 5 faces). Storing the 12 non-zeros
// of each occluded transfer instead measured no faster steps and a 2.4x slower build.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "gi/lpv/light_volume.h"
#include "gi/lpv/propagation.h"

namespace voxgi {

namespace lpv_detail {

constexpr int kLanes = 8;       // cells per run (one AVX register of floats)
constexpr int kChannels = 12;   // colour * 4 + SH coefficient
constexpr int kBounceFloats = 3 * 16 * kLanes;  // per run: a 4x4 matrix per colour per lane

// SH coefficient that carries dimension d (x, y, z): (Y00, Y1-1 ~ y, Y10 ~ z, Y11 ~ x).
constexpr int shOf(int d) { return d == 0 ? 3 : d == 1 ? 1 : 2; }
// The two dimensions other than k, in increasing order (the side faces' normals, see
// propagationTables: faces 1, 2 lie along the first, 3, 4 along the second).
constexpr int otherDim(int k, int i) { return i == 0 ? (k == 0 ? 1 : 0) : (k == 2 ? 1 : 2); }

constexpr int kRunFloats = kChannels * kLanes;    // one run's light: 12 channels of 8 lanes

// The light of an n^3 cascade as blocks of one run each (8 cells along x): a block holds its
// 12 channels one after another, 8 lanes each, and the blocks of a row (y, z) follow each other
// along x. A zero block at both ends of every row and a zero row on every side make neighbours
// outside the grid read zero without a branch.
//
// Why this shape: a step reads a run's sources, writes its output and adds it to the running
// sum; with these blocks each of those is one sequential stream through memory (7 in all: the
// rows at y +- 1 and z +- 1, the row itself, the output, the sum), which the hardware prefetchers
// follow. With 12 channel planes per volume, a step walked 3 x 12 streams, more than they track,
// and waited on memory at 20-30 % of the bandwidth. The neighbours along x are the run's own
// lanes moved by one (two shuffles).
struct SoaLayout {
    int n = 0;
    int runsX = 0;
    std::size_t rowRuns = 0;    // runsX + 2
    std::size_t sy = 0;         // rows along y (and planes along z): n + 2
    std::size_t rowStride = 0;  // floats from one row to the next along y: rowRuns * kRunFloats
    std::size_t size = 0;       // floats in all: rowStride * sy * sy

    SoaLayout() = default;
    explicit SoaLayout(int resolution);
    // The first float of run rx's block in row (y, z).
    std::size_t block(int rx, int y, int z) const {
        return (((std::size_t(z) + 1) * sy + std::size_t(y) + 1) * rowRuns + std::size_t(rx) + 1) * kRunFloats;
    }
    // Channel c (colour * 4 + SH coefficient) of cell (x, y, z).
    std::size_t cell(int x, int y, int z, int c) const {
        return block(x / kLanes, y, z) + std::size_t(c * kLanes + x % kLanes);
    }
    std::size_t runCount() const { return std::size_t(runsX) * std::size_t(n) * std::size_t(n); }
    // Run (rx, y, z) in the operator's numbering (no padding).
    std::size_t run(int rx, int y, int z) const {
        return (std::size_t(z) * std::size_t(n) + std::size_t(y)) * std::size_t(runsX) + std::size_t(rx);
    }
    bool operator==(const SoaLayout& o) const { return n == o.n; }
};

struct SoaLight {
    SoaLayout layout;
    std::vector<float> data;  // layout.size

    void reset(const SoaLayout& l);
    void fromVolume(const LightVolume& v);
    void toVolume(LightVolume& v) const;
};

struct PropagationOperator {
    SoaLayout layout;
    // [run * 6 + axis] -> 5 faces x kLanes pass factors 1 - beta_f, or null when no lane of the
    // run has a blocker on that side.
    std::vector<const float*> pass;
    // [run] -> kBounceFloats (colour, column, row, lane) bounce matrices, or null.
    std::vector<const float*> bounce;
    // Runs with an occluded side, and runs next to a reflecting blocker (counted once, at build).
    std::size_t occludedRuns = 0, bounceRuns = 0;

    PropagationOperator(const BlockerVolume& geometry, const CascadeGrid& grid, const PropagationOptions& options);
    PropagationOperator(const PropagationOperator&) = delete;
    PropagationOperator& operator=(const PropagationOperator&) = delete;

private:
    // The storage `pass` and `bounce` point into, one pool per row of runs (built in parallel).
    std::vector<std::vector<float>> passRows_, bounceRows_;
};

// What one step reads and writes: out = transfer(in); with acc, acc = (acc + carried) + out,
// where carried (optional) is the previous step's output, added by this step for the bricks
// whose carriedActive flag is set (two steps fused in one pass through memory leave the sum to
// the second, in the order single steps add).
struct StepBuffers {
    const SoaLight* in = nullptr;
    SoaLight* out = nullptr;
    SoaLight* acc = nullptr;
    const SoaLight* carried = nullptr;
    const std::uint8_t* carriedActive = nullptr;
};
// The 8^3 bricks a step runs (count.x = runsX; x fastest), and per brick kLanes running sums of
// the magnitudes of its output coefficients, summed over its rows in z then y order.
struct StepBricks {
    glm::ivec3 count{0};
    const std::uint8_t* active = nullptr;
    float* laneTotals = nullptr;
};

// One step for rows [y0, y1) of plane z, the runs of active bricks only. Runs the widest
// instruction set the CPU has; the overload with a level is for tests that compare them. Light
// below FLT_MIN is flushed to zero (a brick whose sums stay 0 sent out no light).
enum class SimdLevel { Baseline, Avx2, Avx512 };
bool simdLevelSupported(SimdLevel level);
SimdLevel bestSimdLevel();
void propagateRows(const PropagationOperator& op, const StepBuffers& buffers, const StepBricks& bricks, int z, int y0,
                   int y1);
void propagateRows(const PropagationOperator& op, const StepBuffers& buffers, const StepBricks& bricks, int z, int y0,
                   int y1, SimdLevel level);

}  // namespace lpv_detail

}  // namespace voxgi
