// Light propagation between the cells of one cascade (seed 000 section 3.10.3), CPU reference.
//
// Each step gathers, for every destination cell, from its 6 face neighbours: the flux a source
// cell sends through each of the 5 destination faces other than the shared one is
//     Phi_f = dOmega_f * I_s(w_sf) * (1 - beta_f),   beta_f = clamp(B(-w_sf), 0, 1),
// with dOmega_f the solid angle of the face seen from the source centre and B the geometry
// volume at the shared face centre; Phi_f is re-emitted from the destination centre as the
// cosine lobe (Phi_f / pi) max(0, n_f . w) about the face normal. The 30 faces around a cell
// tile the whole sphere (5 faces cover the shared face's 2 pi / 3), so in empty space the total
// flux, 4 pi Y00 c0, is carried over exactly; no 4 pi normalization is needed.
//
// Extra bounces: the flux a cell's light loses to a blocker at one of its faces is reflected
// back into the same cell with that blocker's albedo, shaped like the blocker's own SH lobe
// normalized to unit flux. Each bounce therefore carries at most albedo x the incoming flux.
#pragma once

#include <array>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "gi/lpv/light_volume.h"

namespace voxgi {

// The geometry of one (source -> destination) face: derived at start-up, see propagation.cpp.
struct PropagationFace {
    glm::vec3 direction;   // unit, source centre -> face centre
    float solidAngle;      // steradians, seen from the source centre
    glm::vec3 normal;      // the face's outward normal (axis) = lobe direction of the re-emission
};

struct PropagationTables {
    std::array<glm::ivec3, 6> axes;                       // +x -x +y -y +z -z
    std::array<std::array<PropagationFace, 5>, 6> faces;  // [axis][face]; face 0 is the far one
    // The solid angle of the far (front) and side faces of the next cell, for unit cells.
    float frontSolidAngle;
    float sideSolidAngle;
};

const PropagationTables& propagationTables();

// The per-face coefficients both back ends use (2-band SH as vec4, see gi/sh/sh.h).
struct FaceCoefficients {
    glm::vec4 sample;  // dOmega_f * Y(w_sf): dot with a source SH gives the face flux
    glm::vec4 block;   // Y(-w_sf): dot with a blocker SH gives beta
    glm::vec4 lobe;    // cosine lobe about the face normal / pi: unit-flux re-emission
};
struct PropagationKernel {
    std::array<std::array<FaceCoefficients, 5>, 6> faces;
    std::array<glm::mat4, 6> unoccluded;  // sum over the 5 faces of lobe (x) sample
};
const PropagationKernel& propagationKernel();

// Solid angle of the planar convex polygon `corners` seen from `eye` (sum of triangles).
double polygonSolidAngle(glm::dvec3 eye, const std::vector<glm::dvec3>& corners);

struct PropagationOptions {
    bool occlusion = true;
    bool bounces = true;
};

struct PropagationStats {
    std::size_t activeBricks = 0;  // bricks processed in the last step (sparse mode)
    std::size_t totalBricks = 0;
    int stepsRun = 0;              // steps taken: fewer than asked once propagation converged
    bool operatorBuilt = false;    // the operator was built for this call (else kept from the last)
    double operatorMs = 0.0;       // building the transfer matrices from the geometry volume
    // The operator's size: runs of 8 cells, those with an occluded side and those next to a
    // reflecting blocker (they cost more per step and carry their factors through memory).
    std::size_t runs = 0, occludedRuns = 0, bounceRuns = 0;
    double stepsMs = 0.0;          // the iterations
};

// Propagation stops before `steps` once the light that further steps could add (bounded by the
// geometric decay of the last kConvergenceWindow steps' output) is below kConvergenceTolerance
// of the light sent so far, or once no light is left. stepLight holds each step's output (sum
// of coefficient magnitudes); lightSoFar the injected light plus all of them.
constexpr double kConvergenceTolerance = 1e-5;
constexpr int kConvergenceWindow = 8;
bool propagationConverged(const std::vector<double>& stepLight, double lightSoFar);

// Runs up to `steps` iterations (see propagationConverged): accumulated = injected + sum of
// every iteration's output. `sparse` processes only bricks holding light (dilated one brick
// per step).

class CpuPropagator {
public:
    CpuPropagator();
    ~CpuPropagator();
    CpuPropagator(CpuPropagator&&) noexcept;
    CpuPropagator& operator=(CpuPropagator&&) noexcept;

    // The transfer operator built from `geometry` is kept and reused while the geometry
    // volume and options stay the same (a static scene re-propagates without rebuilding it).
    void propagate(const LightVolume& injected, const BlockerVolume& geometry, int steps,
                   const PropagationOptions& options, LightVolume& accumulated, bool sparse = true);
    // One iteration from `in` to `out` (dense), for tests.
    static void step(const LightVolume& in, const BlockerVolume& geometry, const PropagationOptions& options,
                     LightVolume& out);
    const PropagationStats& stats() const { return stats_; }

    // Steps run two at a time in one pass through memory where the planes such a pass keeps in
    // flight fit in cache (up to about 90^3 cells): the sum is read and written once for both
    // steps and the first step's output is read back from cache (20-30 % faster steps at 32^3
    // and 64^3 on one thread; 0-10 % slower at 128^3, where they spill). The light is the same
    // to the bit, except that a stop after the first step of a pair (propagation converged) keeps
    // the second's light, which the convergence test bounds. Tests force either way.
    enum class StepPairs { Auto, Never, Always };
    void setStepPairs(StepPairs pairs) { pairs_ = pairs; }

private:
    struct Work;  // the operator and the working volumes, kept between calls
    std::unique_ptr<Work> work_;
    PropagationStats stats_;
    StepPairs pairs_ = StepPairs::Auto;
};

}  // namespace voxgi
