#include "gi/ddgi/hit_shading.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "gi/ddgi/hit_cache.h"
#include "gi/ddgi/probe_sampling.h"
#include "gi/raytrace/ray_tracer.h"
#include "gi/sampling/sequences.h"

namespace voxgi {

namespace {
constexpr float kPi = 3.14159265358979323846f;
constexpr float kInvPi = 1.0f / kPi;

float smoothstep(float e0, float e1, float x) {
    if (e1 <= e0) return x >= e1 ? 1.0f : 0.0f;
    float t = std::clamp((x - e0) / (e1 - e0), 0.0f, 1.0f);
    return t * t * (3.0f - 2.0f * t);
}
}  // namespace

float ShadowRayVisibility::visible(int, glm::vec3 p, glm::vec3 n, glm::vec3 l, float range) const {
    glm::vec3 origin = p + n * offset_;
    float tMax = std::isfinite(range) ? range * (1.0f - 1e-4f) - offset_ : 1e30f;
    if (tMax <= 0.0f) return 1.0f;
    return tracer_.occluded(origin, l, 0.0f, tMax) ? 0.0f : 1.0f;
}

void lightDirection(const Light& light, glm::vec3 p, glm::vec2 quadSample, glm::vec3* l, float* range) {
    if (light.type == LightType::Directional) {
        *l = -glm::normalize(light.direction);
        *range = INFINITY;
        return;
    }
    glm::vec3 position = light.type == LightType::Quad
                             ? light.position + quadSample.x * light.edgeU + quadSample.y * light.edgeV
                             : light.position;
    glm::vec3 toLight = position - p;
    *range = glm::length(toLight);
    *l = *range > 0.0f ? toLight / *range : glm::vec3(0.0f, 1.0f, 0.0f);
}

namespace {

// A light with its per-frame constants resolved (direction, cone cosines, quad frame), so the
// per-hit work is the geometry alone.
struct PreparedLight {
    LightType type;
    glm::vec3 position, edgeU, edgeV, color, direction, quadNormal;
    float cosOuter = 0.0f, cosInner = 0.0f, area = 0.0f;

    explicit PreparedLight(const Light& light)
        : type(light.type), position(light.position), edgeU(light.edgeU), edgeV(light.edgeV), color(light.color) {
        if (type == LightType::Directional || type == LightType::Spot) direction = glm::normalize(light.direction);
        if (type == LightType::Spot) {
            cosOuter = std::cos(glm::radians(light.outerConeDegrees));
            cosInner = std::cos(glm::radians(light.innerConeDegrees));
        }
        if (type == LightType::Quad) {
            quadNormal = light.quadNormal();
            area = light.area();
        }
    }

    // Irradiance at (p, n) before visibility, the unit direction l toward the light and its
    // distance (infinite for the sun). False when the light cannot contribute.
    bool unshadowed(glm::vec3 p, glm::vec3 n, glm::vec2 quadSample, glm::vec3* e, glm::vec3* l, float* range) const {
        if (type == LightType::Directional) {
            *l = -direction;
            float c = glm::dot(n, *l);
            if (!(c > 0.0f)) return false;
            *e = color * c;
            *range = INFINITY;
            return true;
        }
        glm::vec3 at = position;
        glm::vec3 intensity = color;  // W/sr
        if (type == LightType::Quad) {
            at = position + quadSample.x * edgeU + quadSample.y * edgeV;
            intensity = color * area;
        }
        glm::vec3 toLight = at - p;
        float d2 = glm::dot(toLight, toLight);
        if (!(d2 > 1e-12f)) return false;
        float d = std::sqrt(d2);
        *l = toLight / d;
        float c = glm::dot(n, *l);
        if (c <= 0.0f) return false;
        if (type == LightType::Spot) intensity *= smoothstep(cosOuter, cosInner, glm::dot(-*l, direction));
        else if (type == LightType::Quad) intensity *= std::max(glm::dot(quadNormal, -*l), 0.0f);
        if (glm::max(intensity.x, glm::max(intensity.y, intensity.z)) <= 0.0f) return false;
        *e = intensity * (c / d2);
        *range = d;
        return true;
    }
};

std::vector<PreparedLight> prepareLights(const Scene& scene) {
    std::vector<PreparedLight> lights;
    for (const Light& l : scene.lights) lights.emplace_back(l);
    return lights;
}

// Sum over lights of unshadowed irradiance times visibility(light index, l, range).
template <typename Visible>
glm::vec3 sumLights(const std::vector<PreparedLight>& lights, glm::vec3 p, glm::vec3 n, glm::vec2 quadSample,
                    Visible&& visible) {
    glm::vec3 sum(0.0f);
    for (std::size_t i = 0; i < lights.size(); ++i) {
        glm::vec3 e, l;
        float range;
        if (lights[i].unshadowed(p, n, quadSample, &e, &l, &range)) sum += e * visible(int(i), l, range);
    }
    return sum;
}

}  // namespace

glm::vec3 directIrradiance(const Scene& scene, const LightVisibility& visibility, glm::vec3 p, glm::vec3 n,
                           glm::vec2 quadSample) {
    return sumLights(prepareLights(scene), p, n, quadSample,
                     [&](int i, glm::vec3 l, float range) { return visibility.visible(i, p, n, l, range); });
}

namespace {

struct ShadeContext {
    const Scene& scene;
    const LightVisibility& visibility;
    const ProbeSampler& sampler;
    const RaySet& rays;
    const ProbeTrace& trace;
    const std::vector<int>& probes;
    const std::vector<PreparedLight>& lights;
    std::uint32_t frame;
    float energy;

    // Quad-light sample points of this frame: the offset depends on probe % 7 only, so the
    // 7 x rays points are tabulated once (empty without quad lights).
    const std::vector<glm::vec2>& quadSamples;

    const ProbeSurfel* jobSurfels(std::size_t job) const { return &trace.at(probes[job], rays.fixedRays); }
    const ProbeSurfel& surfel(std::size_t h, int* ray, int* probe) const {
        std::size_t job = h / std::size_t(rays.blendRays);
        *ray = int(h - job * std::size_t(rays.blendRays));
        *probe = probes[job];
        return trace.at(*probe, rays.fixedRays + *ray);
    }
    // The point on quad lights this ray's hit uses this frame (only quad lights read it).
    glm::vec2 quadSample(int ray, int probe) const {
        if (quadSamples.empty()) return glm::vec2(0.5f);
        return quadSamples[std::size_t(probe % 7) * std::size_t(rays.blendRays) + std::size_t(ray)];
    }
};

bool shaded(const ProbeSurfel& s) {
    return !(s.distance < 0.0f) && s.distance < kMissDistance &&
           glm::max(s.diffuseAlbedo.x, glm::max(s.diffuseAlbedo.y, s.diffuseAlbedo.z)) > 0.0f;
}

// Evaluates each group at its representative hit: the probe gather, and in the `all` mode the
// visibility of the first four lights.
// Groups in the order of the probe cage (finest volume) their representative lies in: a
// counting sort, so that consecutive gathers read the same eight probes' tiles from cache
// instead of scattering over the atlases.
std::vector<std::uint32_t> cageOrder(const ShadeContext& c, const HitCache& cache) {
    const ProbeVolume& v = c.sampler.field().volumes().front();
    const std::size_t groups = cache.groups(), cages = std::size_t(v.probeCount());
    std::vector<std::uint32_t> cage(groups), start(cages + 1, 0), order(groups);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, groups, 1024), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t g = r.begin(); g != r.end(); ++g) {
            int ray, probe;
            glm::vec3 x = (c.surfel(cache.representative(g), &ray, &probe).position - v.origin) / v.spacing;
            glm::ivec3 cell = glm::clamp(glm::ivec3(glm::clamp(x, glm::vec3(0.0f), glm::vec3(v.counts))),
                                         glm::ivec3(0), v.counts - 1);
            cage[g] = std::uint32_t(cell.x + v.counts.x * (cell.y + v.counts.y * cell.z));
        }
    });
    for (std::size_t g = 0; g < groups; ++g) ++start[cage[g] + 1];
    for (std::size_t i = 0; i < cages; ++i) start[i + 1] += start[i];
    for (std::size_t g = 0; g < groups; ++g) order[start[cage[g]]++] = std::uint32_t(g);
    return order;
}

// Evaluates each group at its representative hit: the probe gather, and in the `all` mode the
// visibility of the first four lights.
void evaluateGroups(const ShadeContext& c, const HitCache& cache, bool visibility, std::vector<glm::vec3>& irradiance,
                    std::vector<glm::vec4>& lightVisibility, std::atomic<std::int64_t>& queries) {
    const std::size_t groups = cache.groups();
    irradiance.resize(groups);
    if (visibility) lightVisibility.resize(groups);
    const int lights = std::min<int>(int(c.scene.lights.size()), 4);
    const std::vector<std::uint32_t> order = cageOrder(c, cache);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, groups, 256), [&](const tbb::blocked_range<std::size_t>& r) {
        std::int64_t count = 0;
        for (std::size_t k = r.begin(); k != r.end(); ++k) {
            const std::size_t g = order[k];
            int ray, probe;
            const ProbeSurfel& s = c.surfel(cache.representative(g), &ray, &probe);
            irradiance[g] = c.energy > 0.0f
                                ? c.energy * c.sampler.irradiance(s.position, s.normal, -c.rays.blendDirection(ray))
                                : glm::vec3(0.0f);
            if (!visibility) continue;
            glm::vec4 v(-1.0f);
            glm::vec2 u = c.quadSample(ray, probe);
            for (int l = 0; l < lights; ++l) {
                glm::vec3 dir;
                float range;
                lightDirection(c.scene.lights[std::size_t(l)], s.position, u, &dir, &range);
                if (glm::dot(dir, s.normal) <= 0.0f) continue;
                v[l] = c.visibility.visible(l, s.position, s.normal, dir, range);
                ++count;
            }
            lightVisibility[g] = v;
        }
        queries += count;
    });
}

}  // namespace

ShadeStats shadeProbeRays(const Scene& scene, const LightVisibility& visibility, const ProbeSampler& previous,
                          const RaySet& rays, const ProbeTrace& trace, const std::vector<int>& probes,
                          std::uint32_t frame, HitCache* cache, ShadedRays& out) {
    const DdgiDesc& desc = previous.field().desc();
    bool quadLights = false;
    for (const Light& l : scene.lights) quadLights |= l.type == LightType::Quad;
    std::vector<glm::vec2> quadSamples;
    if (quadLights)
        for (int residue = 0; residue < 7; ++residue)
            for (int i = 0; i < rays.blendRays; ++i)
                quadSamples.push_back(r2Sequence(int(frame) * rays.blendRays + i, glm::vec2(0.5f) + 0.137f * float(residue)));
    const std::vector<PreparedLight> prepared = prepareLights(scene);
    const ShadeContext c{scene,  visibility, previous, rays, trace, probes, prepared, frame, desc.energyPreservation,
                         quadSamples};
    const glm::vec3 sky = scene.sky.enabled ? scene.sky.radiance : glm::vec3(0.0f);
    const std::size_t hits = probes.size() * std::size_t(rays.blendRays);
    out.raysPerJob = rays.blendRays;
    out.values.resize(hits);
    ShadeStats stats;
    std::atomic<std::int64_t> queries{0};

    const bool cacheVisibility = desc.hitCache == DdgiHitCache::All && !scene.lights.empty();
    const bool useCache = cache && desc.hitCache != DdgiHitCache::Off && (c.energy > 0.0f || cacheVisibility);
    std::vector<glm::vec3> groupIrradiance;
    std::vector<glm::vec4> groupVisibility;
    if (useCache) {
        float cell = previous.field().volumes().front().minSpacing();
        for (const ProbeVolume& v : previous.field().volumes()) cell = std::min(cell, v.minSpacing());
        cache->group(cell / float(desc.hitCacheCells), probes.size(), std::size_t(rays.blendRays),
                     [&](std::size_t job, std::size_t i, glm::vec3* p, glm::vec3* n) {
                         const ProbeSurfel& s = c.jobSurfels(job)[i];
                         *p = s.position;
                         *n = s.normal;
                         return shaded(s);
                     });
        evaluateGroups(c, *cache, cacheVisibility, groupIrradiance, groupVisibility, queries);
        stats.cacheGroups = std::int64_t(cache->groups());
    }

    std::atomic<std::int64_t> cachedHits{0};
    const std::size_t perJob = std::size_t(rays.blendRays);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, probes.size(), 2), [&](const tbb::blocked_range<std::size_t>& r) {
        std::int64_t count = 0, cached = 0;
        std::vector<std::uint32_t> groups;
        for (std::size_t job = r.begin(); job != r.end(); ++job) {
            const ProbeSurfel* surfels = c.jobSurfels(job);
            groups.resize(perJob);
            for (std::size_t i = 0; i < perJob; ++i) {
                // Group indices first, with the groups' values prefetched (they are scattered).
                std::uint32_t g = useCache ? cache->groupOf(job * perJob + i) : HitCache::kNone;
                groups[i] = g;
                if (g != HitCache::kNone) {
                    __builtin_prefetch(&groupIrradiance[g]);
                    if (cacheVisibility) __builtin_prefetch(&groupVisibility[g]);
                }
            }
            for (std::size_t i = 0; i < perJob; ++i) {
                const ProbeSurfel& s = surfels[i];
                const std::size_t h = job * perJob + i;
                glm::vec4& o = out.values[h];
                if (s.distance >= kMissDistance) {
                    o = glm::vec4(sky, kMissDistance);
                    continue;
                }
                if (!shaded(s)) {
                    // Backfaces carry no light; black front faces only their emission.
                    o = glm::vec4(s.distance < 0.0f ? glm::vec3(0.0f) : s.emission, s.distance);
                    continue;
                }
                glm::vec2 u = c.quadSample(int(i), probes[job]);
                const std::uint32_t g = groups[i];
                glm::vec3 e;
                auto traced = [&](int k, glm::vec3 l, float range) {
                    ++count;
                    return visibility.visible(k, s.position, s.normal, l, range);
                };
                if (g == HitCache::kNone) {
                    e = sumLights(prepared, s.position, s.normal, u, traced);
                    if (c.energy > 0.0f)
                        e += c.energy * previous.irradiance(s.position, s.normal, -rays.blendDirection(int(i)));
                } else if (cacheVisibility) {
                    // The group's visibility; a light the representative did not test (it faced
                    // away) or past the fourth is tested here.
                    const glm::vec4& shared = groupVisibility[g];
                    e = sumLights(prepared, s.position, s.normal, u, [&](int k, glm::vec3 l, float range) {
                            return k < 4 && shared[k] >= 0.0f ? shared[k] : traced(k, l, range);
                        }) + groupIrradiance[g];
                    ++cached;
                } else {
                    e = sumLights(prepared, s.position, s.normal, u, traced) + groupIrradiance[g];
                    ++cached;
                }
                o = glm::vec4(s.emission + s.diffuseAlbedo * kInvPi * e, s.distance);
            }
        }
        queries += count;
        cachedHits += cached;
    });
    stats.shadowQueries = queries.load();
    stats.cachedHits = cachedHits.load();
    return stats;
}

}  // namespace voxgi
