#include "gi/ddgi/ddgi_desc.h"

#include <string>

#include "scenes/errors.h"
#include "shaders/ddgi/limits.h"

namespace voxgi {

namespace {

std::size_t product(glm::ivec3 v) { return std::size_t(v.x) * std::size_t(v.y) * std::size_t(v.z); }

// The surfel buffer holds every probe's rays (52 bytes each) and the atlases 5 KiB per probe:
// sizes that would exhaust memory are refused before anything is allocated.
void requireAffordable(const DdgiDesc& d) {
    // Fitted grids: at most fitCells probes along every axis.
    const glm::ivec3 counts = d.probeCounts.x > 0 ? d.probeCounts : glm::ivec3(d.fitCells);
    const std::size_t probes = product(counts) * std::size_t(d.cascades);
    if (probes > 262144) throw InputError("gi.ddgi.probes: more than 262144 probes over all cascades");
    if (probes * std::size_t(d.raysPerProbe()) > (std::size_t(1) << 24))
        throw InputError("gi.ddgi.rays: probes x rays above 16M rays per frame");
}

// The volume trace runs in GL compute and shades with shadow rays through the volume.
void requireTraceable(const DdgiDesc& d) {
    if (d.trace == DdgiTrace::Triangles) return;
    const char* name = d.trace == DdgiTrace::Volume ? "volume" : "bvh";
    if (!d.gpuBlend())
        throw InputError(std::string("gi.ddgi.trace: ") + name + " traces on the GPU and needs ddgi.backend=gl");
    if (d.directLight != DdgiDirectLight::ShadowRays)
        throw InputError(std::string("gi.ddgi.trace: ") + name +
                         " shades with shadow rays on the GPU; ddgi.direct=occlusion needs trace=triangles");
}

SettingsTable<DdgiDesc> makeTable() {
    using D = DdgiDesc;
    SettingsTable<D> t("ddgi");
    t.counts("probes", &D::probeCounts, 1, 256, "probes per axis; fit: cubic cells, fit_cells on the bounds' longest axis", "fit");
    t.integer("fit_cells", &D::fitCells, 1, 32, "probes = fit: cells along the scene bounds' longest axis");
    t.triple("spacing", &D::spacing, 1e-6, 1e6, "cell size (m); fit: the bounds over the probe counts, probes at cell centres",
             "fit");
    t.integer("rays", &D::rays, 1, 4096, "rotated rays per probe per update (blended)").main();
    t.integer("fixed_rays", &D::fixedRays, 1, 1024, "unrotated classification rays (traced when classify or relocate)");
    t.integer("irradiance_texels", &D::irradianceTexels, 2, 64, "interior irradiance texels per side (the tile adds a border)");
    t.integer("distance_texels", &D::distanceTexels, 2, 64, "interior distance texels per side");
    t.number("hysteresis", &D::hysteresis, 0.0, 1.0, "weight of the previous value in the blend").main();
    t.number("distance_exponent", &D::distanceExponent, 1.0, 1000.0, "sharpness of the distance weights");
    t.number("normal_bias", &D::normalBias, 0.0, 1.0, "in cells (times the smallest spacing)");
    t.number("view_bias", &D::viewBias, 0.0, 1.0, "in cells (times the smallest spacing)");
    t.number("irradiance_gamma", &D::irradianceGamma, 1.0, 16.0, "irradiance is blended and stored as E^(1/gamma)");
    t.number("energy", &D::energyPreservation, 0.0, 1.0,
             "energy-preservation factor on probe irradiance re-used at hits (seed 004: < 1 tames bright scenes)");
    t.number("irradiance_threshold", &D::irradianceThreshold, 0.0, 1e30,
             "encoded change that drops the hysteresis (RTXGI's fast response)");
    t.number("brightness_threshold", &D::brightnessThreshold, 0.0, 1e30,
             "encoded change above which a step is damped to 25 %");
    t.number("backface_threshold", &D::backfaceThreshold, 0.0, 1.0, "fixed-ray backface ratio that turns a probe off");
    t.number("relocation_backface_threshold", &D::relocationBackfaceThreshold, 0.0, 1.0,
             "all-ray backface ratio that moves a probe through the wall");
    t.number("min_frontface_distance", &D::minFrontfaceDistance, 0.0, 0.45, "in cells: relocation keeps probes this far from walls");
    t.flag("classify", &D::classify, "probe states (active, sleeping, off)");
    t.flag("relocate", &D::relocate, "move probes out of walls");
    t.flag("occupancy", &D::occupancy, "also put probes to sleep from the voxel occupancy (voxelizes at start)");
    t.integer("sleep_interval", &D::sleepInterval, 1, 100000, "frames between updates of a sleeping probe (seed 004)");
    t.integer("cascades", &D::cascades, 1, kDdgiMaxVolumes, "camera-centred cascades, spacing doubling outward").main();
    t.choice("scroll", &D::scroll, {{"auto", DdgiScroll::Auto}, {"true", DdgiScroll::On}, {"false", DdgiScroll::Off}},
             "camera-centred volumes scrolling in whole cells; auto: when cascades > 1");
    t.number("forward_offset", &D::forwardOffset, 0.0, 0.5,
             "scrolling volumes centred this fraction of their extent ahead of the camera");
    t.choice("direct", &D::directLight, {{"rays", DdgiDirectLight::ShadowRays}, {"occlusion", DdgiDirectLight::OcclusionProbes}},
             "light visibility at probe-ray hits: shadow rays or occlusion probes (seed 004 ch. 5)");
    t.integer("occlusion_stride", &D::occlusionStride, 1, 4096, "occlusion probes: shadow rays from every n-th hit");
    t.choice("hit_cache", &D::hitCache, {{"off", DdgiHitCache::Off}, {"probes", DdgiHitCache::Probes}, {"all", DdgiHitCache::All}},
             "off: every hit exact; probes: nearby hits share the probe gather; all: and the light visibility");
    t.integer("hit_cache_cells", &D::hitCacheCells, 1, 64, "hit-cache cells per smallest probe spacing");
    t.integer("hit_cache_refresh", &D::hitCacheRefresh, 1, 64,
              "frames between evaluations of a hit-cache cell seen last frame (1: every frame)");
    t.integer("seed", &D::seed, 0, 2147483647, "ray rotations; the same seed and frames give bitwise the same field");
    t.choice("backend", &D::backend, backendChoices(), "blend and border on the GPU (gl) or with the CPU reference (cpu)").main();
    t.choice("trace", &D::trace,
             {{"triangles", DdgiTrace::Triangles}, {"volume", DdgiTrace::Volume}, {"bvh", DdgiTrace::Bvh}},
             "blend rays against the triangles (Embree, CPU), the voxelized scene as NanoVDB (GL compute) or the "
             "triangles in Embree's BVH (GL compute; probes classified in the volume)");
    t.integer("trace_voxels", &D::traceVoxels, 1, 64, "trace = volume or bvh: voxels per smallest probe spacing");
    t.check(requireAffordable);
    t.check(requireTraceable);
    return t;
}

}  // namespace

const SettingsTable<DdgiDesc>& ddgiSettings() {
    static const SettingsTable<DdgiDesc> table = makeTable();
    return table;
}

DdgiDesc readDdgiDesc(const GiSettings& gi) { return ddgiSettings().read(gi); }

}  // namespace voxgi
