#include "gi/ddgi/ddgi_desc.h"

#include <sstream>

#include "scenes/errors.h"

namespace voxgi {

namespace {

// "x,y,z" or a single value for all three axes.
glm::vec3 parseTriple(const GiSettings& gi, const std::string& key, glm::vec3 fallback) {
    if (!gi.has(key)) return fallback;
    std::string text = gi.getString(key, "");
    std::stringstream in(text);
    glm::vec3 v(0.0f);
    int n = 0;
    std::string part;
    while (std::getline(in, part, ',')) {
        if (n == 3) throw InputError("gi." + key + ": expected one value or x,y,z, got '" + text + "'");
        try {
            std::size_t used = 0;
            v[n] = std::stof(part, &used);
            if (used != part.size()) throw std::invalid_argument(part);
        } catch (const std::exception&) {
            throw InputError("gi." + key + ": expected numbers, got '" + text + "'");
        }
        ++n;
    }
    if (n == 1) return glm::vec3(v.x);
    if (n != 3) throw InputError("gi." + key + ": expected one value or x,y,z, got '" + text + "'");
    return v;
}

void requireRange(const std::string& key, double v, double lo, double hi) {
    if (!(v >= lo && v <= hi)) {
        std::ostringstream m;
        m << "gi." << key << ": " << v << " is outside [" << lo << ", " << hi << "]";
        throw InputError(m.str());
    }
}

}  // namespace

DdgiDesc readDdgiDesc(const GiSettings& gi) {
    gi.requireKnown("ddgi", {"probes", "spacing", "rays", "fixed_rays", "irradiance_texels", "distance_texels",
                             "hysteresis", "distance_exponent", "normal_bias", "view_bias", "irradiance_gamma",
                             "energy", "irradiance_threshold", "brightness_threshold", "backface_threshold",
                             "relocation_backface_threshold", "min_frontface_distance", "classify", "occupancy", "relocate",
                             "sleep_interval", "cascades", "scroll", "direct", "occlusion_stride", "hit_cache", "hit_cache_cells", "hit_cache_refresh", "seed",
                             "backend"});
    DdgiDesc d;
    glm::vec3 counts = parseTriple(gi, "ddgi.probes", glm::vec3(0.0f));
    for (int a = 0; a < 3; ++a) {
        requireRange("ddgi.probes", counts[a], 0, 256);
        if (counts[a] != float(int(counts[a]))) throw InputError("gi.ddgi.probes: expected whole numbers");
    }
    d.probeCounts = glm::ivec3(counts);
    if (gi.has("ddgi.probes") && glm::any(glm::lessThan(d.probeCounts, glm::ivec3(1))))
        throw InputError("gi.ddgi.probes: every axis needs at least one probe");
    if (std::size_t(d.probeCounts.x) * std::size_t(d.probeCounts.y) * std::size_t(d.probeCounts.z) > (1u << 20))
        throw InputError("gi.ddgi.probes: more than 1048576 probes");
    d.spacing = parseTriple(gi, "ddgi.spacing", glm::vec3(0.0f));
    for (int a = 0; a < 3; ++a) requireRange("ddgi.spacing", d.spacing[a], 0.0, 1e6);
    if (gi.has("ddgi.spacing") && glm::any(glm::lessThanEqual(d.spacing, glm::vec3(0.0f))))
        throw InputError("gi.ddgi.spacing: must be positive");

    d.rays = gi.getInt("ddgi.rays", d.rays);
    requireRange("ddgi.rays", d.rays, 1, 4096);
    d.fixedRays = gi.getInt("ddgi.fixed_rays", d.fixedRays);
    requireRange("ddgi.fixed_rays", d.fixedRays, 1, 1024);
    d.irradianceTexels = gi.getInt("ddgi.irradiance_texels", d.irradianceTexels);
    requireRange("ddgi.irradiance_texels", d.irradianceTexels, 2, 64);
    d.distanceTexels = gi.getInt("ddgi.distance_texels", d.distanceTexels);
    requireRange("ddgi.distance_texels", d.distanceTexels, 2, 64);
    d.hysteresis = gi.getFloat("ddgi.hysteresis", d.hysteresis);
    requireRange("ddgi.hysteresis", d.hysteresis, 0, 1);
    d.distanceExponent = gi.getFloat("ddgi.distance_exponent", d.distanceExponent);
    requireRange("ddgi.distance_exponent", d.distanceExponent, 1, 1000);
    d.normalBias = gi.getFloat("ddgi.normal_bias", d.normalBias);
    requireRange("ddgi.normal_bias", d.normalBias, 0, 1);
    d.viewBias = gi.getFloat("ddgi.view_bias", d.viewBias);
    requireRange("ddgi.view_bias", d.viewBias, 0, 1);
    d.irradianceGamma = gi.getFloat("ddgi.irradiance_gamma", d.irradianceGamma);
    requireRange("ddgi.irradiance_gamma", d.irradianceGamma, 1, 16);
    d.energyPreservation = gi.getFloat("ddgi.energy", d.energyPreservation);
    requireRange("ddgi.energy", d.energyPreservation, 0, 1);
    d.irradianceThreshold = gi.getFloat("ddgi.irradiance_threshold", d.irradianceThreshold);
    requireRange("ddgi.irradiance_threshold", d.irradianceThreshold, 0, 1e30);
    d.brightnessThreshold = gi.getFloat("ddgi.brightness_threshold", d.brightnessThreshold);
    requireRange("ddgi.brightness_threshold", d.brightnessThreshold, 0, 1e30);
    d.backfaceThreshold = gi.getFloat("ddgi.backface_threshold", d.backfaceThreshold);
    requireRange("ddgi.backface_threshold", d.backfaceThreshold, 0, 1);
    d.relocationBackfaceThreshold = gi.getFloat("ddgi.relocation_backface_threshold", d.relocationBackfaceThreshold);
    requireRange("ddgi.relocation_backface_threshold", d.relocationBackfaceThreshold, 0, 1);
    d.minFrontfaceDistance = gi.getFloat("ddgi.min_frontface_distance", d.minFrontfaceDistance);
    requireRange("ddgi.min_frontface_distance", d.minFrontfaceDistance, 0, 0.45);
    d.classify = gi.getBool("ddgi.classify", d.classify);
    d.relocate = gi.getBool("ddgi.relocate", d.relocate);
    d.occupancy = gi.getBool("ddgi.occupancy", d.occupancy);
    d.sleepInterval = gi.getInt("ddgi.sleep_interval", d.sleepInterval);
    requireRange("ddgi.sleep_interval", d.sleepInterval, 1, 100000);
    d.cascades = gi.getInt("ddgi.cascades", d.cascades);
    requireRange("ddgi.cascades", d.cascades, 1, 8);
    d.scroll = gi.getBool("ddgi.scroll", d.cascades > 1);
    std::string direct = gi.getString("ddgi.direct", "rays");
    if (direct == "rays") d.directLight = DdgiDirectLight::ShadowRays;
    else if (direct == "occlusion") d.directLight = DdgiDirectLight::OcclusionProbes;
    else throw InputError("gi.ddgi.direct: expected rays or occlusion, got '" + direct + "'");
    d.occlusionStride = gi.getInt("ddgi.occlusion_stride", d.occlusionStride);
    requireRange("ddgi.occlusion_stride", d.occlusionStride, 1, 4096);
    std::string cache = gi.getString("ddgi.hit_cache", "all");
    if (cache == "off") d.hitCache = DdgiHitCache::Off;
    else if (cache == "probes") d.hitCache = DdgiHitCache::Probes;
    else if (cache == "all") d.hitCache = DdgiHitCache::All;
    else throw InputError("gi.ddgi.hit_cache: expected off, probes or all, got '" + cache + "'");
    d.hitCacheCells = gi.getInt("ddgi.hit_cache_cells", d.hitCacheCells);
    requireRange("ddgi.hit_cache_cells", d.hitCacheCells, 1, 64);
    d.hitCacheRefresh = gi.getInt("ddgi.hit_cache_refresh", d.hitCacheRefresh);
    requireRange("ddgi.hit_cache_refresh", d.hitCacheRefresh, 1, 64);
    int seed = gi.getInt("ddgi.seed", int(d.seed));
    d.seed = std::uint32_t(seed);
    std::string backend = gi.getString("ddgi.backend", "gpu");
    if (backend != "gpu" && backend != "cpu") throw InputError("gi.ddgi.backend: expected gpu or cpu, got '" + backend + "'");
    d.gpuBlend = backend == "gpu";
    // The surfel buffer holds every probe's rays (52 bytes each) and the atlases 5 KiB per
    // probe: refuse sizes that would exhaust memory rather than die allocating.
    if (d.probeCounts.x > 0) {
        std::size_t probes = std::size_t(d.probeCounts.x) * std::size_t(d.probeCounts.y) *
                             std::size_t(d.probeCounts.z) * std::size_t(d.cascades);
        if (probes > 262144) throw InputError("gi.ddgi.probes: more than 262144 probes over all cascades");
        if (probes * std::size_t(d.raysPerProbe()) > (std::size_t(1) << 24))
            throw InputError("gi.ddgi.rays: probes x rays above 16M rays per frame");
    }
    return d;
}

}  // namespace voxgi
