#include "gi/pathtrace/integrator.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "gi/pathtrace/bsdf.h"

namespace voxgi::pt {

namespace {
float powerHeuristic(float a, float b) {
    float a2 = a * a, b2 = b * b;
    return a2 + b2 > 0.0f ? a2 / (a2 + b2) : 0.0f;
}
float maxComponent(glm::vec3 v) { return std::max(v.x, std::max(v.y, v.z)); }
}  // namespace

glm::vec3 offsetOrigin(glm::vec3 p, glm::vec3 geometric, glm::vec3 direction, float sceneScale) {
    // 8 to 16 units in the last place of the larger of the scene's size and the point's distance
    // from the origin: hit points are rebuilt from vertices and barycentrics, and Embree's plane
    // tests round, at that magnitude, so the surface left behind is never found again; and the
    // offset stays a fixed fraction of float precision at any scale and any translation (an
    // absolute length would lift a 0.1 mm scene off its surfaces).
    constexpr float kUlps = 8.0f / 8388608.0f;  // 8 * 2^-23
    float scale = sceneScale + std::max(std::abs(p.x), std::max(std::abs(p.y), std::abs(p.z)));
    float side = glm::dot(geometric, direction) >= 0.0f ? 1.0f : -1.0f;
    return p + geometric * (side * kUlps * scale);
}

float rayOffsetScale(const Scene& scene) {
    Bounds b = scene.bounds();
    return b.valid() ? std::max(glm::length(b.extent()), 1e-6f) : 1.0f;
}

Integrator::Integrator(const Scene& scene, const RayTracer& tracer, int maxBounces)
    : scene_(scene), tracer_(tracer), lights_(scene), environment_(scene.sky),
      maxBounces_(maxBounces > 0 ? maxBounces : kBounceGuard), sceneScale_(rayOffsetScale(scene)) {}

bool Integrator::segmentOccluded(glm::vec3 from, glm::vec3 q, glm::vec3 nq) const {
    // The far end leaves the emitter the way rays leave surfaces and the segment stops at that
    // offset point: the emitter's own plane never counts as a blocker, whatever the angles, the
    // scene's size or its distance from the origin (each end's offset is measured at that end).
    glm::vec3 to = offsetOrigin(q, nq, from - q, sceneScale_);
    glm::vec3 segment = to - from;
    float length = glm::length(segment);
    return length > 0.0f && tracer_.occluded(from, segment / length, 0.0f, length);
}

glm::vec3 leavingPoint(const RayHit& hit, glm::vec3 direction, float sceneScale) {
    // The smooth surface lies on the side the vertex normals face: rays leaving to that side of
    // the shading normal start from it, offset outwards even when they dip below the triangle's
    // plane (which is what they clear the neighbouring facets by). Others (a refraction into a
    // low-poly sphere, light through a leaf) start at the triangle, offset to their side.
    if (glm::dot(direction, hit.shadingNormal) > 0.0f)
        return offsetOrigin(hit.smoothPosition, hit.geometricNormal, hit.shadingNormal, sceneScale);
    return offsetOrigin(hit.position, hit.geometricNormal, direction, sceneScale);
}

namespace {
// Where the shadow ray towards a delta light seen along `direction` at `distance` stops.
float shadowRayEnd(float distance) {
    return std::isinf(distance) ? std::numeric_limits<float>::infinity() : distance * (1.0f - 1e-5f);
}
}  // namespace

glm::vec3 Integrator::sampleLights(const Bsdf& bsdf, const RayHit& hit, glm::vec3 u, glm::vec2 uDisc,
                                   float arrivalPdfArea, std::uint32_t& rays) const {
    const glm::vec3 p = hit.position;
    glm::vec3 sum(0.0f);
    for (std::size_t i = 0; i < lights_.deltaCount(); ++i) {
        LightSample ls = lights_.sampleDelta(i, p, uDisc);
        if (maxComponent(ls.radiance) <= 0.0f) continue;
        glm::vec3 f = bsdf.eval(ls.direction);
        if (maxComponent(f) <= 0.0f) continue;
        // The same path, previous vertex - this one - light, is also made by a light subpath
        // landing here and the previous vertex connecting to it.
        float weight = 1.0f;
        if (arrivalPdfArea > 0.0f)
            weight = powerHeuristic(arrivalPdfArea, lights_.emissionPdfArea(i, ls.direction, ls.distance,
                                                                            std::abs(glm::dot(hit.geometricNormal, ls.direction))));
        glm::vec3 o = leavingPoint(hit, ls.direction, sceneScale_);
        ++rays;
        if (!tracer_.occluded(o, ls.direction, 0.0f, shadowRayEnd(ls.distance))) sum += f * ls.radiance * weight;
    }
    const float skyShare = environmentShare();
    if (u.z < skyShare) {
        const EnvironmentSampler::Sample es = environment_.sample(glm::vec2(u.x, u.y));
        const float pdf = es.pdf * skyShare;
        if (pdf > 0.0f) {
            float bsdfPdf;
            glm::vec3 f = bsdf.evalPdf(es.direction, &bsdfPdf);
            if (maxComponent(f) > 0.0f) {
                ++rays;
                if (!tracer_.occluded(leavingPoint(hit, es.direction, sceneScale_), es.direction, 0.0f,
                                      std::numeric_limits<float>::infinity()))
                    sum += f * scene_.sky.radianceAt(es.direction) * (powerHeuristic(pdf, bsdfPdf) / pdf);
            }
        }
    } else if (lights_.hasEmitters()) {
        const float select = std::min((u.z - skyShare) / (1.0f - skyShare), 0.99999994f);
        LightSample ls = lights_.sampleEmitter(p, glm::vec2(u.x, u.y), select);
        ls.pdf *= 1.0f - skyShare;
        if (ls.pdf > 0.0f) {
            float bsdfPdf;
            glm::vec3 f = bsdf.evalPdf(ls.direction, &bsdfPdf);
            if (maxComponent(f) > 0.0f) {
                ++rays;
                if (!segmentOccluded(leavingPoint(hit, ls.direction, sceneScale_), ls.position, ls.normal))
                    sum += f * (ls.radiance / (1.0f - skyShare)) * powerHeuristic(ls.pdf, bsdfPdf);
            }
        }
    }
    return sum;
}

float Integrator::environmentShare() const {
    if (!environment_.active()) return 0.0f;
    return lights_.hasEmitters() ? 0.5f : 1.0f;
}

std::uint32_t Integrator::traceLightPath(const PathSampler& sampler, LightVertex& out) const {
    out = LightVertex{};
    const EmittedRay e = lights_.sampleEmission(sampler.get3D(0));
    if (!(e.pdf > 0.0f) || maxComponent(e.intensity) <= 0.0f) return 0;
    const RayHit hit = tracer_.intersect(e.origin, e.direction);
    std::uint32_t rays = 1;
    if (!hit.hit) return rays;
    const glm::vec3 toLight = -e.direction;
    const float cosine = std::abs(glm::dot(hit.geometricNormal, toLight));
    if (!(cosine > 0.0f)) return rays;
    const Material& material = scene_.materials[hit.material];
    const glm::vec3 albedo = tracer_.albedoAt(hit);
    // Only surfaces a camera path takes this light at by next-event estimation: no delta BSDFs.
    if (!Bsdf(material, albedo, toLight, hit.geometricNormal, hit.shadingNormal, hit.frontFace).hasSmoothPart())
        return rays;
    // The light must also pass the shadow ray next-event estimation would trace from here,
    // which starts from the smooth surface (leavingPoint) where the vertex normals bulge out:
    // light ray and shadow ray then need not agree, and the two strategies must see one scene.
    if (hit.smoothPosition != hit.position) {
        ++rays;
        if (tracer_.occluded(leavingPoint(hit, toLight, sceneScale_), toLight, 0.0f, shadowRayEnd(hit.t))) return rays;
    }
    out.position = hit.position;
    out.material = hit.material;
    out.geometricNormal = hit.geometricNormal;
    out.shadingNormal = hit.shadingNormal;
    out.albedo = albedo;
    out.toLight = toLight;
    out.pdfArea = e.pdf * cosine / (hit.t * hit.t);
    out.flux = e.intensity / (e.pdf * cosine);
    if (!(out.pdfArea > 0.0f) || !std::isfinite(out.pdfArea) || !std::isfinite(maxComponent(out.flux)))
        out = LightVertex{};
    return rays;
}

glm::vec3 Integrator::connect(const Bsdf& bsdf, const RayHit& hit, const LightVertices& pool, float u,
                              std::uint32_t& rays) const {
    if (pool.vertices.empty()) return glm::vec3(0.0f);
    const LightVertex& v = pool.vertices[std::min(std::size_t(u * float(pool.vertices.size())), pool.vertices.size() - 1)];
    if (!v.valid()) return glm::vec3(0.0f);
    const glm::vec3 d = v.position - hit.position;
    const float d2 = glm::dot(d, d);
    if (!(d2 > 0.0f)) return glm::vec3(0.0f);
    const glm::vec3 w = d / std::sqrt(d2);
    float pdfHere;
    const glm::vec3 fHere = bsdf.evalPdf(w, &pdfHere);
    const float cosThere = std::abs(glm::dot(v.geometricNormal, w));
    if (maxComponent(fHere) <= 0.0f || !(cosThere > 0.0f)) return glm::vec3(0.0f);
    // The light vertex as the camera path would meet it, arriving along w.
    const Bsdf there(scene_.materials[v.material], v.albedo, -w, v.geometricNormal, v.shadingNormal,
                     glm::dot(v.geometricNormal, w) < 0.0f);
    const glm::vec3 fThere = there.eval(v.toLight);
    if (maxComponent(fThere) <= 0.0f) return glm::vec3(0.0f);
    const float geometry = cosThere / d2;
    const glm::vec3 c = fHere * fThere * v.flux * (geometry * powerHeuristic(v.pdfArea, pdfHere * geometry));
    if (maxComponent(c) <= 0.0f) return glm::vec3(0.0f);
    ++rays;
    return segmentOccluded(leavingPoint(hit, w, sceneScale_), v.position, v.geometricNormal) ? glm::vec3(0.0f) : c;
}

PathSample Integrator::trace(glm::vec3 origin, glm::vec3 direction, const PathSampler& sampler,
                             const LightVertices* lightVertices) const {
    const bool connecting = lightVertices && !lightVertices->vertices.empty();
    PathSample out;
    glm::vec3 throughput(1.0f);
    float radianceScale = 1.0f;
    float previousPdf = 0.0f;
    bool previousDelta = true;  // the camera: what it sees directly gets full weight
    glm::vec3 previousPosition = origin;
    auto deposit = [&](int scatterings, glm::vec3 radiance) {
        (scatterings <= 1 ? out.direct : out.indirect) += radiance;
    };

    for (int depth = 0;; ++depth) {
        RayHit hit = tracer_.intersect(origin, direction);
        ++out.rays;
        if (!hit.hit) {
            // A tabulated sky is also sampled by next-event estimation; a constant one only
            // by the BSDF, where it takes full weight.
            float weight = 1.0f;
            if (!previousDelta && environment_.active()) weight = powerHeuristic(previousPdf, environmentShare() * environment_.pdf(direction));
            deposit(depth, throughput * scene_.sky.radianceAt(direction) * weight);
            break;
        }
        const Material& material = scene_.materials[hit.material];
        // The bounce's decisions: light sample, BSDF sample, roulette, light-vertex choice, the
        // direction in a sun's disc (gi/pathtrace/sampler.h). Their points are computed while
        // the texels of the albedo load: that cache miss was most of a texture lookup's time.
        const std::uint32_t decision = 1 + 5 * std::uint32_t(std::min(depth, 1 << 20));
        tracer_.prefetchAlbedo(hit);
        glm::vec3 uLight(0.0f), uBsdf(0.0f);
        glm::vec2 uDisc(0.0f);
        if (depth < maxBounces_) {
            uLight = sampler.get3D(decision);
            uDisc = sampler.get2D(decision + 4);
            uBsdf = sampler.get3D(decision + 1);
        }
        glm::vec3 albedo = tracer_.albedoAt(hit);
        if (depth == 0) {
            out.albedo = albedo;
            out.depth = hit.t;
            glm::vec3 ng = hit.frontFace ? hit.geometricNormal : -hit.geometricNormal;
            out.normal = glm::dot(hit.shadingNormal, ng) < 0.0f ? -hit.shadingNormal : hit.shadingNormal;
        }
        if (hit.frontFace && material.isEmissive()) {
            float weight = 1.0f;
            if (!previousDelta) {
                float lightPdf = (1.0f - environmentShare()) *
                                 lights_.emitterPdf(hit.mesh, hit.triangle, previousPosition, hit.position,
                                                    -glm::dot(hit.geometricNormal, direction));
                weight = powerHeuristic(previousPdf, lightPdf);
            }
            deposit(depth, throughput * material.emission * weight);
        }
        if (depth >= maxBounces_) break;

        glm::vec3 wo = -direction;
        Bsdf bsdf(material, albedo, wo, hit.geometricNormal, hit.shadingNormal, hit.frontFace);
        if (bsdf.hasSmoothPart()) {
            // A light-vertex connection from the previous vertex could have made this path's
            // next-event samples of delta lights when that vertex sampled a smooth lobe.
            const float arrivalPdfArea = connecting && depth >= 1 && !previousDelta
                                             ? previousPdf * std::abs(glm::dot(hit.geometricNormal, direction)) / (hit.t * hit.t)
                                             : 0.0f;
            deposit(depth + 1, throughput * sampleLights(bsdf, hit, uLight, uDisc, arrivalPdfArea, out.rays));
            if (connecting && depth + 1 < maxBounces_)
                deposit(depth + 2, throughput * connect(bsdf, hit, *lightVertices, sampler.get1D(decision + 3), out.rays));
        }

        BsdfSample s;
        if (!bsdf.sample(uBsdf, s)) break;
        throughput *= s.weight;
        out.scatterings = depth + 1;
        previousPdf = s.pdf;
        previousDelta = s.delta;
        previousPosition = hit.position;
        radianceScale *= s.radianceScale;
        if (depth >= 3) {
            // Russian roulette keeps the estimate unbiased: survivors carry 1 / q. Survival
            // follows the throughput (without the radiance scaling of refractions, which undoes
            // itself on the way out), so weights stay at 1 even for albedo 0.99 and paths that
            // lose no energy are never cut; kBounceGuard ends those.
            float q = maxComponent(throughput) / radianceScale;
            if (q < 1.0f) {
                if (!(sampler.get1D(decision + 2) < q)) break;
                throughput /= q;
            }
        }
        if (maxComponent(throughput) <= 0.0f) break;
        origin = leavingPoint(hit, s.direction, sceneScale_);
        direction = s.direction;
    }
    return out;
}

}  // namespace voxgi::pt
