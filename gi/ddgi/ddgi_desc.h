// DDGI settings (the counterpart of RTXGI's DDGIVolumeDesc): the `gi.ddgi.*` keys. Defaults are
// the members' initial values; ranges and docs are in the table (ddgi_desc.cpp), printed by
// `voxgi methods ddgi`.
#pragma once

#include <cstdint>
#include <string>

#include <glm/glm.hpp>

#include "gi/backend.h"
#include "gi/settings_table.h"
#include "scenes/scene.h"

namespace voxgi {

// The update's stages as the frame plan and the frame's timers name them.
inline constexpr const char* kDdgiTraceStage = "ddgi.trace";
inline constexpr const char* kDdgiShadeStage = "ddgi.shade";
inline constexpr const char* kDdgiBlendStage = "ddgi.blend";
inline constexpr const char* kDdgiBorderStage = "ddgi.border";
inline constexpr const char* kDdgiClassifyStage = "ddgi.classify";

enum class DdgiDirectLight {
    ShadowRays,       // one shadow ray per light per probe-ray hit
    OcclusionProbes,  // visibility reconstructed from an occlusion-probe field (seed 004 ch. 5)
};

// Sharing of probe-ray hit shading between nearby hits within a frame (gi/ddgi/hit_cache.h).
enum class DdgiHitCache {
    Off,     // every hit gathers the probes and tests its lights itself (exact)
    Probes,  // hits in one cache cell and normal bin share one probe gather
    All,     // ... and one light-visibility test per light (up to four lights)
};

// What the blend rays are traced against.
enum class DdgiTrace {
    Triangles,  // the scene's triangles with Embree on the CPU, shaded on the CPU (the reference)
    Volume,     // the voxelized scene as NanoVDB, traced and shaded on the GPU (backend gl)
    Bvh,        // the triangles in Embree's BVH, traced and shaded on the GPU; probes classified in the volume
};

// Camera-centred scrolling of the probe volumes.
enum class DdgiScroll {
    Auto,  // when there are cascades
    On,
    Off,
};

struct DdgiDesc {
    // Grid: zero counts/spacing = fit the scene bounds: cubic cells, fitCells of them along the
    // longest axis (so a long, low scene gets more probes along its length than its height);
    // probes sit at cell centres so none lies on the bounding walls.
    glm::ivec3 probeCounts{0};
    glm::vec3 spacing{0.0f};
    int fitCells = 8;
    int rays = 256;               // rotated rays per probe per update, used for blending
    int fixedRays = 32;           // unrotated rays used only for classification and relocation
    int irradianceTexels = 8;     // interior texels per side (tile = texels + 2 with the border)
    int distanceTexels = 16;
    float hysteresis = 0.97f;     // weight of the previous value in the blend
    float distanceExponent = 50.0f;
    float normalBias = 0.1f;      // in cells (fraction of the smallest spacing)
    float viewBias = 0.1f;        // in cells
    float irradianceGamma = 5.0f; // irradiance is blended and stored as E^(1/gamma)
    float energyPreservation = 1.0f;  // scales the probe irradiance re-used at ray hits
    float irradianceThreshold = 0.25f;  // encoded change that drops hysteresis (fast response)
    float brightnessThreshold = 0.10f;  // encoded change above which a step is damped to 25 %
    float backfaceThreshold = 0.25f;    // fixed-ray backface ratio that turns a probe off
    float relocationBackfaceThreshold = 0.1f;  // all-ray backface ratio that moves a probe
    float minFrontfaceDistance = 0.3f;  // in cells: relocation pushes probes this far from walls
    bool classify = true;
    bool occupancy = false;       // also classify from the voxel occupancy (gi/ddgi/occupancy_query.h)
    bool relocate = true;
    int sleepInterval = 10;       // a sleeping probe updates every this many frames
    int cascades = 1;             // > 1: camera-centred cascades, spacing doubling outward
    DdgiScroll scroll = DdgiScroll::Auto;  // camera-centred volume(s) scrolling in whole cells
    // Scrolling volumes centre this fraction of their extent ahead of the camera (as clpv's
    // lpv.forward_offset): most probes where the camera looks, some behind for light from there.
    float forwardOffset = 0.25f;
    DdgiDirectLight directLight = DdgiDirectLight::ShadowRays;
    int occlusionStride = 4;      // occlusion probes: shadow rays from every n-th blend ray's hit
    DdgiHitCache hitCache = DdgiHitCache::All;
    int hitCacheCells = 2;        // hit-cache cells per smallest probe spacing
    // Frames between evaluations of a hit-cache cell: a cell also present last frame re-uses
    // last frame's values on the frames between (1: evaluate every cell every frame).
    int hitCacheRefresh = 2;
    int seed = 1;                 // random ray rotations; same seed, same frames, same result
    Backend backend = Backend::Gl;  // blend on the GPU (GL compute) or with the CPU reference
    DdgiTrace trace = DdgiTrace::Triangles;
    int traceVoxels = 16;         // trace = volume: voxels per smallest probe spacing

    bool gpuBlend() const { return backend == Backend::Gl; }
    bool scrolls() const { return scroll == DdgiScroll::Auto ? cascades > 1 : scroll == DdgiScroll::On; }
    int fixedRayCount() const { return (classify || relocate) ? fixedRays : 0; }
    int raysPerProbe() const { return rays + fixedRayCount(); }
};

const SettingsTable<DdgiDesc>& ddgiSettings();
// Reads `ddgi.*` over the defaults; InputError names the key of an unknown or refused value and
// of a probe count or ray budget that would exhaust memory.
DdgiDesc readDdgiDesc(const GiSettings& gi);

}  // namespace voxgi
