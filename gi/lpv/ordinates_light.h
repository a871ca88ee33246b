// The light volumes of `lpv.transport=ordinates` (gi/lpv/ordinates.h): per cascade, the transport
// with its surfaces from the voxelized scene (kept while the cascade stays), the ring and inner
// sources of each update (split by gi/lpv/cascades.h's shares, as the SH light is), their
// irradiance cubes in one pool of bricks with the cascades' brick tables (on the GPU: buffers,
// shaders/shared/light_bricks.h), and the apply pass that reads them.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "gi/lpv/cascades.h"
#include "gi/lpv/gl_ordinates.h"
#include "gi/lpv/lpv_desc.h"
#include "gi/lpv/ordinates.h"
#include "gi/lpv/tap_masks.h"
#include "gi/technique.h"
#include "gl/program.h"
#include "gl/resources.h"

namespace voxgi {

class RayTracer;
class SkyVolume;
class SparseGeometryVolume;
class TriangleBvhGl;
struct Scene;

class OrdinatesLight {
public:
    // `scene` must outlive this (lpv.tap_visibility traces its triangles).
    OrdinatesLight(const LpvDesc& desc, const Scene& scene);
    ~OrdinatesLight();

    // Makes the transports of cascades that moved, their surfaces from `voxels` (level = cascade;
    // may be null: no surfaces but the emitters'). Returns whether any was made.
    bool place(const std::vector<CascadePlacement>& placements, const SparseGeometryVolume* voxels);
    // Starts an update's sources; surfels are added from every RSM face and the sky bounce.
    void clearSources();
    void addSurfels(const SurfelSource& surfels);
    // The sky's bounce from every voxelized surface: the sky-lighting volume's irradiance on it,
    // reflected with its albedo (the SH transport's sky bounce has only the surfaces on screen).
    void addSkyBounce(const SkyVolume& sky);
    // Transports every cascade's sources and uploads the irradiance cubes.
    void solve();
    void apply(const GBufferView& g) const;

    struct Stats {
        double solveMs = 0.0;
        int sweeps = 0;              // the most any light set needed
        double emittedWatts = 0.0;   // summed over cascades' ring sets (each surfel once)
        double outsideWatts = 0.0;   // surfels outside every cascade
        std::size_t surfaceCells = 0;
        double leftWatts = 0.0;      // reflections not yet carried (lpv.sweeps=N continues them)
        bool converged = true;       // every light set's left-over under kOrdinatesConverged of its sources
        std::size_t bricks = 0;      // allocated bricks, summed over cascades (each holds a ring and an inner slot)
        std::size_t gridBricks = 0;  // bricks the cascades' grids span (what lpv.sparse=false allocates)
        std::size_t poolBytes = 0;   // the brick pool: ring and inner irradiance cubes of every brick
        double tapMasksMs = 0.0;     // lpv.tap_visibility=cells: masks traced this update (0: kept)
    };
    const Stats& stats() const { return stats_; }
    // The irradiance cube of cascade c, ring + inner, in its transport's bricks (dumps, tests).
    IrradianceBricks irradiance(std::size_t c) const;
    const OrdinatesTransport& transport(std::size_t c) const { return *transports_.at(c); }

private:
    LpvDesc desc_;
    std::vector<CascadePlacement> placements_;
    std::vector<std::unique_ptr<OrdinatesTransport>> transports_;
    std::unique_ptr<GlOrdinates> gl_;  // lpv.backend=gl: the sweeps on the GPU
    std::vector<OrdinatesTransport::Sources> ring_, inner_;
    // Per cascade, ring then inner: the reflections the last solve left (lpv.sweeps=N).
    std::vector<std::vector<glm::vec3>> carry_;
    // Lays the cascades' slots out in the pool (ring then inner, cascade by cascade) and uploads
    // the brick tables when a transport's bricks changed.
    void layOutPool();
    // The GPU's brick pool (vec4, per light set [face][slot][brick cell]) and the cascades' brick tables one
    // after the other (int per brick: slot within its cascade, -1 none).
    gl::Handle pool_, tables_;
    std::size_t poolCap_ = 0, tablesCap_ = 0;
    std::vector<std::size_t> firstSlot_;         // per cascade, ring then inner
    std::vector<int> tableStart_;                // per cascade
    std::vector<std::uint64_t> tableRevisions_;  // per cascade: the transport geometry the tables hold
    gl::Program program_;
    std::unique_ptr<TriangleBvhGl> triangles_;  // lpv.tap_visibility=rays
    float tapRayOffset_ = 0.0f;
    // lpv.tap_visibility=cells: per cascade, its cells' masks (gi/lpv/tap_masks.h) for the
    // transport geometry they were traced for, and all of them on the GPU, cascade after cascade.
    const Scene& scene_;
    std::unique_ptr<RayTracer> maskTracer_;
    std::vector<TapMasks> masks_;
    std::vector<std::uint64_t> maskRevisions_;
    gl::Handle masksBuffer_;
    std::size_t masksCap_ = 0;
    // masksBuffer_: every cascade's cell table (TapMasks::cells, pointing into all the masks),
    // then all the masks. Per cascade: where its table starts; and where the masks start.
    std::vector<int> maskBase_;
    int masksStart_ = 0;
    // Traces the masks of cascades whose transport geometry changed and uploads them all.
    void updateTapMasks();
    Stats stats_;
};

}  // namespace voxgi
