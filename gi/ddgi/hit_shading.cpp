#include "gi/ddgi/hit_shading.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "gi/ddgi/hit_cache.h"
#include "gi/ddgi/probe_sampling.h"
#include "gi/raytrace/ray_tracer.h"
#include "gi/sampling/sequences.h"
#include "gi/sky/sky_volume.h"
#include "shaders/shared/constants.h"
#include "shaders/shared/light_model.h"

namespace voxgi {

float ShadowRayVisibility::visible(int, glm::vec3 p, glm::vec3 n, glm::vec3 l, float range) const {
    glm::vec3 origin = p + n * offset_;
    float tMax = std::isfinite(range) ? range * (1.0f - 1e-4f) - offset_ : 1e30f;
    if (tMax <= 0.0f) return 1.0f;
    return tracer_.occluded(origin, l, 0.0f, tMax) ? 0.0f : 1.0f;
}

namespace {

// A scene light packed for the shared light model (shaders/shared/light_model.h), once per
// frame, so the per-hit work is the geometry alone.
struct PreparedLight {
    shading::PackedLight packed;
    bool dark;  // emits nothing: never worth a shadow ray

    explicit PreparedLight(const Light& light)
        : packed(shading::packLight(light)),
          dark(!(glm::max(light.emission.x, glm::max(light.emission.y, light.emission.z)) > 0.0f)) {}

    glm::vec3 emission() const { return glm::vec3(packed.emission); }

    // The light as seen from p before the receiver's cosine and visibility; a zero falloff when
    // it cannot reach p whatever the normal.
    shading::IncidentLight incident(glm::vec3 p, glm::vec2 quadSample) const {
        if (dark) return shading::IncidentLight{};
        return shading::evaluateLight(packed, p, quadSample);
    }

    // Irradiance e at (p, n) before visibility, with the light as seen from p (its direction and
    // distance for the shadow test). False when the light cannot contribute.
    bool unshadowed(glm::vec3 p, glm::vec3 n, glm::vec2 quadSample, glm::vec3& e,
                    shading::IncidentLight& incident) const {
        incident = this->incident(p, quadSample);
        if (!(incident.falloff > 0.0f)) return false;
        const float c = glm::dot(n, incident.direction);
        if (!(c > 0.0f)) return false;
        e = incident.irradiance * c;
        return true;
    }
};

std::vector<PreparedLight> prepareLights(const Scene& scene) {
    std::vector<PreparedLight> lights;
    for (const Light& l : scene.lights) lights.emplace_back(l);
    return lights;
}

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

    // Quad-light sample points of this frame (quadLightSamples).
    const std::vector<glm::vec2>& quadSamples;
    const ProbeSky& sky;

    // Irradiance at a hit from the previous field (times the energy factor) and the sky volume.
    glm::vec3 gathered(glm::vec3 position, glm::vec3 normal, glm::vec3 toProbe) const {
        glm::vec3 e(0.0f);
        if (energy > 0.0f) e = energy * sampler.irradiance(position, normal, toProbe);
        if (sky.volume) e += sky.volume->sampleIrradiance(position, normal);
        return e;
    }

    const ProbeSurfel* jobSurfels(std::size_t job) const { return &trace.at(probes[job], rays.fixedRays); }
    // The point on quad lights this ray's hit uses this frame (only quad lights read it).
    glm::vec2 quadSample(int ray, int probe) const {
        if (quadSamples.empty()) return glm::vec2(0.5f);
        return quadSamples[std::size_t(probe % kQuadSampleSets) * std::size_t(rays.blendRays) + std::size_t(ray)];
    }
};

// Groups in the order of the probe cage (finest volume) their representative lies in: a
// counting sort, so that consecutive gathers read the same eight probes' tiles from cache
// instead of scattering over the atlases.
const std::vector<std::uint32_t>& cageOrder(const ShadeContext& c, const HitCache& cache, ShadeWorkspace& w) {
    const ProbeVolume& v = c.sampler.field().volumes().front();
    const std::size_t groups = cache.groups(), cages = std::size_t(v.probeCount());
    std::vector<std::uint32_t>&cage = w.cage, &start = w.start, &order = w.order;
    const std::uint32_t skip = std::uint32_t(cages);  // groups not due this frame
    cage.resize(groups);
    start.assign(cages + 2, 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, groups, 1024), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t g = r.begin(); g != r.end(); ++g) {
            if (!w.due[g]) {
                cage[g] = skip;
                continue;
            }
            glm::vec3 x = (cache.representativePosition(g) - v.origin) / v.spacing;
            glm::ivec3 cell = glm::clamp(glm::ivec3(glm::clamp(x, glm::vec3(0.0f), glm::vec3(v.counts))),
                                         glm::ivec3(0), v.counts - 1);
            cage[g] = std::uint32_t(cell.x + v.counts.x * (cell.y + v.counts.y * cell.z));
        }
    });
    for (std::size_t g = 0; g < groups; ++g) ++start[cage[g] + 1];
    for (std::size_t i = 0; i <= cages; ++i) start[i + 1] += start[i];
    order.resize(start[cages]);  // the due groups only
    for (std::size_t g = 0; g < groups; ++g)
        if (cage[g] != skip) order[start[cage[g]]++] = std::uint32_t(g);
    return order;
}

// What a group shares, per group: the probe irradiance and, in the `all` mode, per light (the
// first kSharedLights) the vector falloff * visibility * l seen from the representative, so a
// hit adds emission * max(n . v, 0) with its own normal. A light the representative faced away
// from has no tested visibility: w = 1 marks it, and a hit that faces it tests it itself.
constexpr int kSharedLights = 4;
struct GroupValues {
    int stride = 1;                  // vec4s per group: irradiance, then the shared lights
    int lights = 0;                  // shared lights
    std::vector<glm::vec4>& values;  // group * stride + ...
};

// Every parameter of the scene's lights, to tell whether last frame's group values saw the
// same lights.
std::vector<float> lightFingerprint(const Scene& scene) {
    std::vector<float> f;
    for (const Light& l : scene.lights) {
        f.push_back(float(int(l.type)));
        for (const glm::vec3& v : {l.position, l.direction, l.emission, l.edgeU, l.edgeV})
            f.insert(f.end(), {v.x, v.y, v.z});
        f.insert(f.end(), {l.innerConeDegrees, l.outerConeDegrees});
    }
    return f;
}

// Evaluates each group at its representative hit, or copies last frame's values for a cell
// that had a group last frame and is not due (every `refresh` frames, staggered by key).
// Returns the groups evaluated.
std::int64_t evaluateGroups(const ShadeContext& c, const HitCache& cache, bool shareLights, int refresh,
                            GroupValues& out, ShadeWorkspace& workspace, std::atomic<std::int64_t>& queries) {
    const std::size_t groups = cache.groups();
    out.lights = shareLights ? std::min<int>(int(c.lights.size()), kSharedLights) : 0;
    out.stride = 1 + out.lights;
    std::swap(workspace.previousValues, out.values);
    std::vector<float> lights = lightFingerprint(c.scene);
    const bool reuse = refresh > 1 && workspace.previousStride == out.stride && workspace.previousLights == lights;
    workspace.previousStride = out.stride;
    workspace.previousLights = std::move(lights);
    out.values.resize(groups * std::size_t(out.stride));
    const std::size_t stride = std::size_t(out.stride);
    // Copies first: what is left to evaluate goes in cage order below.
    std::vector<std::uint32_t>& due = workspace.due;
    due.assign(groups, 1);
    if (reuse)
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, groups, 1024), [&](const tbb::blocked_range<std::size_t>& r) {
            for (std::size_t g = r.begin(); g != r.end(); ++g) {
                const std::uint32_t before = cache.previousGroup(g);
                if (before == HitCache::kNone ||
                    (std::uint32_t(cache.groupKey(g) * 0x9E3779B97F4A7C15ull >> 40) + c.frame) % std::uint32_t(refresh) == 0)
                    continue;
                std::copy_n(&workspace.previousValues[std::size_t(before) * stride], stride, &out.values[g * stride]);
                due[g] = 0;
            }
        });
    const std::vector<std::uint32_t>& order = cageOrder(c, cache, workspace);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, order.size(), 256), [&](const tbb::blocked_range<std::size_t>& r) {
        std::int64_t count = 0;
        for (std::size_t k = r.begin(); k != r.end(); ++k) {
            const std::size_t g = order[k];
            const std::size_t h = cache.representative(g);
            const int probe = int(h / std::size_t(c.rays.blendRays));
            const int ray = int(h - std::size_t(probe) * std::size_t(c.rays.blendRays));
            const glm::vec3 position = cache.representativePosition(g), normal = cache.representativeNormal(g);
            glm::vec4* v = &out.values[g * std::size_t(out.stride)];
            v[0] = glm::vec4(c.gathered(position, normal, -c.rays.blendDirection(ray)), 0.0f);
            const glm::vec2 u = c.quadSample(ray, probe);
            for (int l = 0; l < out.lights; ++l) {
                v[1 + l] = glm::vec4(0.0f);
                const shading::IncidentLight incident = c.lights[std::size_t(l)].incident(position, u);
                if (!(incident.falloff > 0.0f)) continue;
                const glm::vec3 dir = incident.direction;
                if (!(glm::dot(dir, normal) > 0.0f)) {
                    v[1 + l] = glm::vec4(incident.falloff * dir, 1.0f);
                    continue;
                }
                ++count;
                const float visible = c.visibility.visible(l, position, normal, dir, incident.distance);
                v[1 + l] = glm::vec4(incident.falloff * visible * dir, 0.0f);
            }
        }
        queries += count;
    });
    return std::int64_t(order.size());
}

}  // namespace

namespace {
// Each residue's R2 sequence starts from its own offset, so neighbouring probes see other points.
glm::vec2 quadSampleOffset(int residue) { return glm::vec2(0.5f) + 0.137f * float(residue); }
}  // namespace

std::vector<glm::vec2> quadLightSamples(const Scene& scene, int blendRays, std::uint32_t frame) {
    std::vector<glm::vec2> samples;
    if (!hasQuadLights(scene)) return samples;
    samples.reserve(std::size_t(kQuadSampleSets) * std::size_t(blendRays));
    for (int residue = 0; residue < kQuadSampleSets; ++residue)
        for (int i = 0; i < blendRays; ++i)
            samples.push_back(r2Sequence(int(frame) * blendRays + i, quadSampleOffset(residue)));
    return samples;
}

bool hasQuadLights(const Scene& scene) {
    for (const Light& l : scene.lights)
        if (l.type == LightType::Quad) return true;
    return false;
}

glm::vec2 quadSampleStart(int residue, int blendRays, std::uint32_t frame) {
    return r2Sequence(int(frame) * blendRays, quadSampleOffset(residue));
}

bool hitCacheUsed(const DdgiDesc& desc, const Scene& scene) {
    if (desc.hitCache == DdgiHitCache::Off) return false;
    return desc.energyPreservation > 0.0f || (desc.hitCache == DdgiHitCache::All && !scene.lights.empty());
}

float hitCacheCellSize(const ProbeField& field) {
    return field.smallestSpacing() / float(field.desc().hitCacheCells);
}

void groupProbeHits(HitCache& cache, const ProbeField& field, const RaySet& rays, const ProbeTrace& trace) {
    cache.group(hitCacheCellSize(field), std::size_t(field.probeCount()), std::size_t(rays.blendRays),
                [&](std::size_t probe, std::size_t i, glm::vec3* p, glm::vec3* n) {
                    if (trace.work[probe] != ProbeWork::Full) return false;
                    const ProbeSurfel& s = trace.at(int(probe), rays.fixedRays + int(i));
                    *p = trace.position(rays, int(probe), rays.fixedRays + int(i));
                    *n = s.normal;
                    return shadedHit(s);
                });
}

ShadeStats shadeProbeRays(const Scene& scene, const LightVisibility& visibility, const ProbeSampler& previous,
                          const RaySet& rays, const ProbeTrace& trace, const std::vector<int>& probes,
                          std::uint32_t frame, const HitCache* grouped, ShadedRays& out, ShadeWorkspace* workspace,
                          const ProbeSky& sky) {
    const DdgiDesc& desc = previous.field().desc();
    const std::vector<glm::vec2> quadSamples = quadLightSamples(scene, rays.blendRays, frame);
    const std::vector<PreparedLight> prepared = prepareLights(scene);
    const ShadeContext c{scene,  visibility, previous, rays, trace, probes, prepared, frame, desc.energyPreservation,
                         quadSamples, sky};
    // Misses see the sky along their ray (one lookup per blend direction, the same for every
    // probe), or nothing when the frame lights surfaces with the sky itself.
    std::vector<glm::vec3> skyAtMiss(std::size_t(rays.blendRays), glm::vec3(0.0f));
    if (sky.atMisses)
        for (int i = 0; i < rays.blendRays; ++i) skyAtMiss[std::size_t(i)] = scene.sky.radianceAt(rays.blendDirection(i));
    const std::size_t hits = probes.size() * std::size_t(rays.blendRays);
    out.raysPerJob = rays.blendRays;
    out.values.resize(hits);
    ShadeStats stats;
    std::atomic<std::int64_t> queries{0};

    const HitCache* cache = grouped && hitCacheUsed(desc, scene) ? grouped : nullptr;
    ShadeWorkspace local;
    if (!workspace) workspace = &local;
    GroupValues shared{1, 0, workspace->groupValues};
    if (cache) {
        const auto t0 = std::chrono::steady_clock::now();
        stats.groupsEvaluated = evaluateGroups(c, *cache, desc.hitCache == DdgiHitCache::All, desc.hitCacheRefresh,
                                               shared, *workspace, queries);
        stats.groupsMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        stats.cacheGroups = std::int64_t(cache->groups());
    }

    glm::vec3 lightColour[kSharedLights];
    for (int k = 0; k < shared.lights; ++k) lightColour[k] = prepared[std::size_t(k)].emission();
    std::atomic<std::int64_t> cachedHits{0};
    const auto hitsStart = std::chrono::steady_clock::now();
    const std::size_t perJob = std::size_t(rays.blendRays);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, probes.size(), 2), [&](const tbb::blocked_range<std::size_t>& r) {
        std::int64_t count = 0, cached = 0;
        std::vector<std::uint32_t> groups;
        for (std::size_t job = r.begin(); job != r.end(); ++job) {
            const ProbeSurfel* surfels = c.jobSurfels(job);
            const std::size_t firstHit = std::size_t(probes[job]) * perJob;
            groups.resize(perJob);
            for (std::size_t i = 0; i < perJob; ++i) {
                // Group indices first, with the groups' values prefetched (they are scattered).
                std::uint32_t g = cache ? cache->groupOf(firstHit + i) : HitCache::kNone;
                groups[i] = g;
                if (g != HitCache::kNone) __builtin_prefetch(&shared.values[std::size_t(g) * std::size_t(shared.stride)]);
            }
            for (std::size_t i = 0; i < perJob; ++i) {
                const ProbeSurfel& s = surfels[i];
                glm::vec4& o = out.values[job * perJob + i];
                if (s.distance >= kMissDistance) {
                    o = glm::vec4(skyAtMiss[i], kMissDistance);
                    continue;
                }
                if (!shadedHit(s)) {
                    // Backfaces carry no light; black front faces only their emission.
                    o = glm::vec4(s.distance < 0.0f ? glm::vec3(0.0f) : trace.emission[s.emitter], s.distance);
                    continue;
                }
                const std::uint32_t g = groups[i];
                auto hitPosition = [&] {
                    return trace.origins[std::size_t(probes[job])] + s.distance * rays.blendDirection(int(i));
                };
                // One light exactly at this hit: its own light point and shadow ray.
                auto exact = [&](int k) {
                    const glm::vec3 position = hitPosition();
                    glm::vec3 e;
                    shading::IncidentLight incident;
                    if (!prepared[std::size_t(k)].unshadowed(position, s.normal, c.quadSample(int(i), probes[job]), e,
                                                             incident))
                        return glm::vec3(0.0f);
                    ++count;
                    return e * visibility.visible(k, position, s.normal, incident.direction, incident.distance);
                };
                glm::vec3 e(0.0f);
                int firstExact = 0;     // lights from here on are evaluated at this hit
                unsigned untested = 0;  // and the shared ones set here
                if (g == HitCache::kNone) {
                    e = c.gathered(hitPosition(), s.normal, -rays.blendDirection(int(i)));
                } else {
                    // Shared lights without branches on the cosine (a hit faces a light or not
                    // about at random); the rare light the representative did not test goes
                    // through exact().
                    const glm::vec4* v = &shared.values[std::size_t(g) * std::size_t(shared.stride)];
                    e = glm::vec3(v[0]);
                    for (int k = 0; k < shared.lights; ++k) {
                        const float cosine = glm::dot(s.normal, glm::vec3(v[1 + k]));
                        const float facing = cosine > 0.0f ? cosine : 0.0f;
                        e += lightColour[k] * (v[1 + k].w == 0.0f ? facing : 0.0f);
                        untested |= unsigned(v[1 + k].w != 0.0f && cosine > 0.0f) << k;
                    }
                    firstExact = shared.lights;
                    ++cached;
                }
                // One call site, so that exact() is inlined into this loop.
                for (int k = 0; k < int(prepared.size()); ++k)
                    if (k >= firstExact || (untested >> k & 1u)) e += exact(k);
                o = glm::vec4(trace.emission[s.emitter] + s.diffuseAlbedo() * shading::kInvPi * e, s.distance);
            }
        }
        queries += count;
        cachedHits += cached;
    });
    stats.hitsMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - hitsStart).count();
    stats.shadowQueries = queries.load();
    stats.cachedHits = cachedHits.load();
    return stats;
}

}  // namespace voxgi
