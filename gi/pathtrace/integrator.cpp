#include "gi/pathtrace/integrator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "gi/pathtrace/bsdf.h"
#include "shaders/shared/constants.h"

namespace voxgi::pt {

namespace {
float powerHeuristic(float a, float b) {
    float a2 = a * a, b2 = b * b;
    return a2 + b2 > 0.0f ? a2 / (a2 + b2) : 0.0f;
}
float maxComponent(glm::vec3 v) { return std::max(v.x, std::max(v.y, v.z)); }
// Connection m of kConnections from one vertex: stratified over the pool by one sample point.
float connectionPick(float u, int m) { return (u + float(m)) * (1.0f / float(kConnections)); }
void prefetchLightVertex(const LightVertices& pool, float u) {
    const char* at = reinterpret_cast<const char*>(&pool.pick(u));
    __builtin_prefetch(at);
    __builtin_prefetch(at + sizeof(LightVertex) - 1);
}
// For MIS against an emitter's light subpaths: the area pdf of one reaching a surface from the
// emitter point (cosine-weighted: cos at the emitter / pi over the distance squared, times the
// point's pdf `pointPdf`) over next-event estimation's area pdf of that point (solid-angle
// `neePdf` x the same cosine over the distance squared): the two factors cancel to this.
float emitterLightArea(float cosAtSurface, float pointPdf, float neePdf) {
    return cosAtSurface * pointPdf / (shading::kPi * neePdf);
}
// The power heuristic's form of a pdf (or of a ratio of pdfs) in the recursive MIS quantities.
float mis(float pdf) { return pdf * pdf; }
// The first of bounce `depth`'s decisions (integrator.h: bounce k uses 1 + 5k .. 5 + 5k).
std::uint32_t bounceDecision(int depth) { return 1 + 5 * std::uint32_t(std::min(depth, 1 << 20)); }
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

Integrator::Integrator(const Scene& scene, const RayTracer& tracer, int maxBounces, bool caustics)
    : scene_(scene), tracer_(tracer), lights_(scene), environment_(scene.sky),
      maxBounces_(maxBounces > 0 ? maxBounces : kBounceGuard), caustics_(caustics), sceneScale_(rayOffsetScale(scene)) {}

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

float Integrator::reverseArea(const Bsdf& bsdf, glm::vec3 onwards, const CameraHistory& history) {
    return bsdf.seenFrom(onwards).pdf(bsdf.wo()) * history.at(history.surfaces).toPreviousArea;
}

template <class ReverseAtK>
float Integrator::longerLightSubpaths(const CameraHistory& history, float lightAreaAtK, ReverseAtK reverseAtK,
                                      int lightSurfaces) const {
    // Strategy j joins v_j to v_(j+1), the light subpath covering v_(j+1) .. v_n; the one
    // evaluated is j = k. Going one surface further towards the camera multiplies its pdf by
    // (light subpath's pdf of v_j) / (camera subpath's); it exists while the camera subpath
    // keeps a surface (j >= 1), the light subpath is within kMaxLightVertices (n - j), and
    // neither subpath met a delta lobe on the way (a zero pdf).
    const int k = history.surfaces;
    const int first = std::max(1, k + lightSurfaces - maxLightVertices());
    float sum = 0.0f, product = 1.0f, light = lightAreaAtK;
    for (int i = k; i - 1 >= first; --i) {
        const float camera = history.at(i).arrival;
        if (!(camera > 0.0f) || !(light > 0.0f)) break;
        product *= mis(light / camera);
        sum += product;
        if (i - 2 < first) break;  // no strategy further on: the reverse pdf is not needed
        light = i == k ? reverseAtK() : history.at(i).reverse;
    }
    return sum;
}

bool Integrator::deltaVisible(const RayHit& hit, const LightSample& ls, std::uint32_t& rays) const {
    ++rays;
    return !tracer_.occluded(leavingPoint(hit, ls.direction, sceneScale_), ls.direction, 0.0f, shadowRayEnd(ls.distance));
}

void Integrator::deltaShadows(const Bsdf& bsdf, const RayHit& hit, glm::vec2 uDisc, EarlyDeltas& out,
                              std::uint32_t& rays) const {
    out.visible = 0;
    const std::size_t count = std::min(lights_.deltaCount(), kEarlyDeltaShadows);
    for (std::size_t i = 0; i < count; ++i) {
        const LightSample ls = lights_.sampleDelta(i, hit.position, uDisc);
        if (i < kKeptDeltaSamples) out.kept[i] = ls;
        if (maxComponent(ls.radiance) > 0.0f && bsdf.mayReflect(ls.direction) && deltaVisible(hit, ls, rays))
            out.visible |= std::uint64_t(1) << i;
    }
}

glm::vec3 Integrator::sampleLights(const Bsdf& bsdf, const RayHit& hit, glm::vec3 u, glm::vec2 uDisc,
                                   const EarlyDeltas& earlyDeltas, const CameraHistory* history, std::uint32_t& rays) const {
    const glm::vec3 p = hit.position;
    glm::vec3 sum(0.0f);
    for (std::size_t i = 0; i < lights_.deltaCount(); ++i) {
        const bool early = i < kEarlyDeltaShadows;  // its shadow ray traced by deltaShadows
        if (early && !(earlyDeltas.visible >> i & 1u)) continue;
        const LightSample ls = i < kKeptDeltaSamples ? earlyDeltas.kept[i] : lights_.sampleDelta(i, p, uDisc);
        if (maxComponent(ls.radiance) <= 0.0f) continue;
        glm::vec3 f = bsdf.eval(ls.direction);
        if (maxComponent(f) <= 0.0f) continue;
        // Light subpaths from this light make the same path too, joined at any of its edges.
        float weight = 1.0f;
        if (history) {
            const float cosine = std::abs(glm::dot(hit.geometricNormal, ls.direction));
            const float emitted = lights_.emissionPdfArea(i, ls.direction, ls.distance, cosine);
            if (emitted > 0.0f) {
                weight = 1.0f / (1.0f + longerLightSubpaths(*history, emitted,
                                                            [&] { return reverseArea(bsdf, ls.direction, *history); }, 0));
            }
        }
        if (early || deltaVisible(hit, ls, rays)) sum += f * ls.radiance * weight;
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
                // Light subpaths from the emitter make the same path too, joined at any edge.
                float weight = powerHeuristic(ls.pdf, bsdfPdf);
                if (history && ls.lightPathPdfArea > 0.0f) {
                    const float cosine = std::abs(glm::dot(hit.geometricNormal, ls.direction));
                    weight = 1.0f / (1.0f + mis(bsdfPdf / ls.pdf) +
                                     longerLightSubpaths(*history, emitterLightArea(cosine, ls.lightPathPdfArea, ls.pdf),
                                                         [&] { return reverseArea(bsdf, ls.direction, *history); }, 0));
                }
                if (!segmentOccluded(leavingPoint(hit, ls.direction, sceneScale_), ls.position, ls.normal))
                    sum += f * (ls.radiance / (1.0f - skyShare)) * weight;
            }
        }
    }
    return sum;
}

float Integrator::environmentShare() const {
    if (!environment_.active()) return 0.0f;
    return lights_.hasEmitters() ? 0.5f : 1.0f;
}

std::uint32_t Integrator::traceLightPath(const PathSampler& sampler, std::vector<LightVertex>& out) const {
    const EmittedRay e = lights_.sampleEmission(sampler.get3D(0), sampler.get2D(1));
    if (!(e.pdf > 0.0f) || maxComponent(e.intensity) <= 0.0f) return 0;
    const bool fromEmitter = e.emitter >= 0;
    // Recursive MIS quantities (light_paths.h) before the next surface's distance and cosine
    // are known: this subpath's pdf of the light's point and direction against next-event
    // estimation's of the point (1 for a delta light: every one is sampled; an emitter's from
    // the first surface, below) and, for an emitter, a camera path hitting it.
    float misArea = 1.0f / mis(e.pdf);
    const float emitterCosine = fromEmitter ? glm::dot(e.normal, e.direction) : 0.0f;
    float misLonger = fromEmitter ? mis(emitterCosine / e.pdf) : 0.0f;
    glm::vec3 power = e.intensity / e.pdf;  // the subpath's throughput
    glm::vec3 carried(1.0f);                // its BSDFs' part, for roulette
    glm::vec3 origin = fromEmitter ? offsetOrigin(e.origin, e.normal, e.direction, sceneScale_) : e.origin;
    glm::vec3 direction = e.direction;
    std::uint32_t rays = 0;
    const int surfaces = maxLightVertices();
    for (int j = 1; j <= surfaces; ++j) {
        const RayHit hit = tracer_.intersect(origin, direction);
        ++rays;
        if (!hit.hit) break;
        const glm::vec3 toLight = -direction;
        const float cosine = std::abs(glm::dot(hit.geometricNormal, toLight));
        if (!(cosine > 0.0f)) break;
        if (j == 1 && hit.smoothPosition != hit.position) {
            // The light must also pass the shadow ray next-event estimation would trace from
            // here, which starts from the smooth surface (leavingPoint) where the vertex normals
            // bulge out: light ray and shadow ray then need not agree, and the two strategies
            // must see one scene.
            ++rays;
            const glm::vec3 from = leavingPoint(hit, toLight, sceneScale_);
            if (fromEmitter ? segmentOccluded(from, e.origin, e.normal)
                            : tracer_.occluded(from, toLight, 0.0f, shadowRayEnd(hit.t)))
                break;
        }
        if (j == 1 && fromEmitter)
            misArea *= mis((1.0f - environmentShare()) * lights_.emitterPdf(e.emitter, hit.position, e.origin, emitterCosine) *
                           emitterCosine / (hit.t * hit.t));
        const Material& material = scene_.materials[hit.material];
        const glm::vec3 albedo = tracer_.albedoAt(hit);
        // Only surfaces a camera path takes this light at by next-event estimation or a
        // connection: no delta BSDFs.
        const Bsdf bsdf(material, albedo, toLight, hit.geometricNormal, hit.shadingNormal, hit.frontFace);
        if (!bsdf.hasSmoothPart()) break;
        misArea *= mis(hit.t * hit.t) / mis(cosine);
        misLonger /= mis(cosine);
        LightVertex v;
        v.position = hit.position;
        v.material = hit.material;
        v.geometricNormal = hit.geometricNormal;
        v.scatterings = std::uint32_t(j);
        v.shadingNormal = hit.shadingNormal;
        v.misArea = misArea;
        v.albedo = albedo;
        v.misLonger = misLonger;
        v.toLight = toLight;
        v.flux = power / cosine;
        if (!std::isfinite(misArea) || !std::isfinite(misLonger) || !std::isfinite(maxComponent(v.flux))) break;
        out.push_back(v);
        if (j == surfaces) break;

        // On, the way a camera path would have come: sampled by the BSDF seen from the light,
        // and carrying what the camera path's BSDF seen from the new direction gives.
        const std::uint32_t decision = 2 * std::uint32_t(j);
        BsdfSample s;
        if (!bsdf.sample(sampler.get3D(decision), s) || s.delta || !(s.pdf > 0.0f)) break;
        float reversePdf;
        const glm::vec3 f = bsdf.seenFrom(s.direction).evalPdf(toLight, &reversePdf);
        const float cosOut = std::abs(glm::dot(hit.geometricNormal, s.direction));
        const glm::vec3 step = f * (cosOut / (cosine * s.pdf));
        if (!(maxComponent(step) > 0.0f)) break;
        power *= step;
        carried *= step;
        misLonger = mis(cosOut / s.pdf) * (misLonger * mis(reversePdf) + misArea);
        misArea = 1.0f / mis(s.pdf);
        if (j >= 2) {
            // Russian roulette, as camera paths: survivors carry 1 / q.
            const float q = maxComponent(carried);
            if (q < 1.0f) {
                if (!(sampler.get1D(decision + 1) < q)) break;
                carried /= q;
                power /= q;
            }
        }
        origin = leavingPoint(hit, s.direction, sceneScale_);
        direction = s.direction;
    }
    return rays;
}

bool Integrator::connection(const Bsdf& bsdf, const RayHit& hit, const LightVertices& pool, float u,
                            const CameraHistory& history, Connection& out) const {
    const LightVertex& v = pool.pick(u);
    if (!v.valid() || history.surfaces + int(v.scatterings) > maxBounces_) return false;
    const glm::vec3 d = v.position - hit.position;
    const float d2 = glm::dot(d, d);
    if (!(d2 > 0.0f)) return false;
    const glm::vec3 w = d / std::sqrt(d2);
    float pdfHere;
    const glm::vec3 fHere = bsdf.evalPdf(w, &pdfHere);
    const float cosThere = std::abs(glm::dot(v.geometricNormal, w));
    const float cosHere = std::abs(glm::dot(hit.geometricNormal, w));
    if (maxComponent(fHere) <= 0.0f || !(cosThere > 0.0f) || !(cosHere > 0.0f)) return false;
    // The light vertex as the camera path would meet it, arriving along w.
    const Bsdf there(scene_.materials[v.material], v.albedo, -w, v.geometricNormal, v.shadingNormal,
                     glm::dot(v.geometricNormal, w) < 0.0f);
    float pdfThereOnwards;  // the camera subpath going on from there to the light subpath's previous vertex
    const glm::vec3 fThere = there.evalPdf(v.toLight, &pdfThereOnwards);
    if (maxComponent(fThere) <= 0.0f) return false;
    const float geometry = cosThere / d2;
    // MIS over the strategies with a longer camera subpath (the recursion the light vertex
    // carries) and with a longer light subpath (the camera history).
    const float cameraLonger = mis(pdfHere * geometry) * (v.misArea + v.misLonger * mis(pdfThereOnwards));
    const float lightAreaHere = there.seenFrom(v.toLight).pdf(-w) * cosHere / d2;
    const float lightLonger = longerLightSubpaths(history, lightAreaHere, [&] { return reverseArea(bsdf, w, history); },
                                                  int(v.scatterings));
    // One vertex of the pool stands for the expected sum over one subpath's vertices.
    const float share = float(pool.vertices.size()) / float(pool.paths);
    out.contribution = fHere * fThere * v.flux * (geometry * share / (1.0f + cameraLonger + lightLonger));
    if (!(out.contribution.x + out.contribution.y + out.contribution.z > 0.0f) ||
        !std::isfinite(out.contribution.x + out.contribution.y + out.contribution.z))
        return false;
    out.from = leavingPoint(hit, w, sceneScale_);
    out.to = v.position;
    out.toNormal = v.geometricNormal;
    out.scatterings = history.surfaces + int(v.scatterings);
    return true;
}

template <class Deposit>
void Integrator::connect(const Bsdf& bsdf, const RayHit& hit, const LightVertices& pool, glm::vec2 u,
                         const CameraHistory& history, Deposit deposit, std::uint32_t& rays) const {
    // kConnections candidates, stratified over the pool by u.x; one shadow ray, for the
    // candidate u.y picks in proportion to its unoccluded contribution (Popov et al. 2015's
    // probabilistic connections): the estimate of their mean is unbiased, and the candidates
    // that matter (near, facing, bright) are the ones traced.
    Connection candidates[kConnections];
    float weights[kConnections];
    float total = 0.0f;
    for (int m = 0; m < kConnections; ++m) {
        const bool valid = connection(bsdf, hit, pool, connectionPick(u.x, m), history, candidates[m]);
        const glm::vec3& c = candidates[m].contribution;
        weights[m] = valid ? c.x + c.y + c.z : 0.0f;
        total += weights[m];
    }
    if (!(total > 0.0f)) return;
    int pick = 0;
    float running = 0.0f;
    const float target = u.y * total;
    for (int m = 0; m < kConnections; ++m) {
        if (!(weights[m] > 0.0f)) continue;
        pick = m;
        running += weights[m];
        if (target < running) break;
    }
    const Connection& c = candidates[pick];
    ++rays;
    if (!segmentOccluded(c.from, c.to, c.toNormal))
        deposit(c.scatterings, c.contribution * (total / (weights[pick] * float(kConnections))));
}

struct Integrator::PathState {
    PathState(const PathStart& start, const LightVertices* pool, PathSample& result);
    void deposit(int scatterings, glm::vec3 radiance) { (scatterings <= 1 ? out.direct : out.indirect) += radiance; }

    PathSampler sampler;
    const LightVertices* lightVertices;  // null: no connections
    const RayHit* firstHit;
    PathSample& out;
    glm::vec3 throughput{1.0f};
    float radianceScale = 1.0f;
    float previousPdf = 0.0f;
    bool previousDelta = true;  // the camera: what it sees directly gets full weight
    bool diffuseOnly = false;  // without caustics: past a surface with a diffuse lobe
    glm::vec3 previousPosition;
    float previousCosine = 0.0f;  // |geometric normal . direction| at the previous surface
    CameraHistory history;        // kept only for connections
    glm::vec3 origin, direction;
    int depth = 0;
    bool done = false;
    // Carried from one stage of the bounce to the next.
    glm::vec2 uConnect{0.0f};
    RawHit raw;
    RayHit hit;
    glm::vec3 uLight{0.0f}, uBsdf{0.0f};
    glm::vec2 uDisc{0.0f};
    std::optional<Bsdf> bsdf;
    EarlyDeltas deltas;
};

PathSample Integrator::trace(glm::vec3 origin, glm::vec3 direction, const PathSampler& sampler,
                             const LightVertices* lightVertices, const RayHit* firstHit) const {
    PathSample out;
    const PathStart start{origin, direction, sampler, firstHit};
    traceBatch(&start, 1, lightVertices, &out);
    return out;
}

void Integrator::traceBatch(const PathStart* starts, int n, const LightVertices* lightVertices, PathSample* out) const {
    // Each bounce of every path in stages, each stage over all paths before the next. The hits'
    // triangle records, then their albedos' texels, are cache misses (a fifth of Sponza's time,
    // one path at a time): here each is requested for all paths in one tight loop, so the misses
    // overlap, and read a stage later. (On the AMD VM a prefetch holds up retirement until its
    // line arrives, so prefetches spread between other work stalled as loads did; issued back
    // to back they wait once for all.) The paths' arithmetic is the same either way, and so is
    // the image.
    const bool connecting = lightVertices && !lightVertices->vertices.empty();
    std::vector<PathState> paths;
    paths.reserve(std::size_t(n));
    for (int i = 0; i < n; ++i) paths.emplace_back(starts[i], connecting ? lightVertices : nullptr, out[i]);
    for (bool active = true; active;) {
        for (PathState& path : paths)
            if (!path.done) findSurface(path);
        for (const PathState& path : paths)
            if (!path.done && !(path.depth == 0 && path.firstHit)) tracer_.prefetchRecord(path.raw);
        for (PathState& path : paths) {
            if (path.done) continue;
            if (path.depth == 0 && path.firstHit)
                path.hit = *path.firstHit;
            else
                tracer_.hitRecord(path.raw, path.direction, path.hit);
        }
        for (const PathState& path : paths)
            if (!path.done && path.hit.hit) tracer_.prefetchAlbedo(path.hit);
        for (PathState& path : paths)
            if (!path.done) enterSurface(path);
        active = false;
        for (PathState& path : paths) {
            if (path.done) continue;
            leaveSurface(path);
            active = active || !path.done;
        }
    }
}

Integrator::PathState::PathState(const PathStart& start, const LightVertices* pool, PathSample& result)
    : sampler(start.sampler), lightVertices(pool), firstHit(start.firstHit), out(result), previousPosition(start.origin),
      origin(start.origin), direction(start.direction) {
    out = PathSample{};
}

void Integrator::findSurface(PathState& path) const {
    // The light vertices this bounce connects to are picked now and their cache lines
    // requested, so that they load while Embree traces (a pool of light subpaths is
    // megabytes, and each pick a random miss).
    const std::uint32_t decision = bounceDecision(path.depth);
    path.uConnect = path.lightVertices ? path.sampler.get2D(decision + 3) : glm::vec2(0.0f);
    if (path.lightVertices)
        for (int m = 0; m < kConnections; ++m) prefetchLightVertex(*path.lightVertices, connectionPick(path.uConnect.x, m));
    if (path.depth == 0 && path.firstHit) return;
    path.raw = tracer_.intersectRaw(path.origin, path.direction);
}

void Integrator::enterSurface(PathState& path) const {
    PathSample& out = path.out;
    const int depth = path.depth;
    const glm::vec3 direction = path.direction;
    const RayHit& hit = path.hit;
    ++out.rays;
    if (!hit.hit) {
        // A tabulated sky is also sampled by next-event estimation; a constant one only
        // by the BSDF, where it takes full weight.
        float weight = 1.0f;
        if (!path.previousDelta && environment_.active())
            weight = powerHeuristic(path.previousPdf, environmentShare() * environment_.pdf(direction));
        path.deposit(depth, path.throughput * scene_.sky.radianceAt(direction) * weight);
        path.done = true;
        return;
    }
    const Material& material = scene_.materials[hit.material];
    // The bounce's decisions: light sample, BSDF sample, roulette, light-vertex choice, the
    // direction in a sun's disc (gi/pathtrace/sampler.h).
    const std::uint32_t decision = bounceDecision(depth);
    path.uLight = glm::vec3(0.0f);
    path.uBsdf = glm::vec3(0.0f);
    path.uDisc = glm::vec2(0.0f);
    if (depth < maxBounces_) {
        // Read only by an emitter or sky sample (delta lights take uDisc alone).
        if (lights_.hasEmitters() || environment_.active()) path.uLight = path.sampler.get3D(decision);
        if (lights_.hasSunDisc()) path.uDisc = path.sampler.get2D(decision + 4);
        path.uBsdf = path.sampler.get3D(decision + 1);
    }
    if (depth == 0) {
        out.depth = hit.t;
        glm::vec3 ng = hit.frontFace ? hit.geometricNormal : -hit.geometricNormal;
        out.normal = glm::dot(hit.shadingNormal, ng) < 0.0f ? -hit.shadingNormal : hit.shadingNormal;
    }
    if (hit.frontFace && material.isEmissive()) {
        float weight = 1.0f;
        if (!path.previousDelta) {
            float lightPdf = (1.0f - environmentShare()) *
                             lights_.emitterPdf(hit.mesh, hit.triangle, path.previousPosition, hit.position,
                                                -glm::dot(hit.geometricNormal, direction));
            weight = powerHeuristic(path.previousPdf, lightPdf);
            const float pointPdf = path.lightVertices ? lights_.emissionPointPdf(hit.mesh, hit.triangle) : 0.0f;
            if (pointPdf > 0.0f && lightPdf > 0.0f) {
                // Next-event estimation at the previous surface, and light subpaths from here
                // joined at any edge, make the same path.
                const CameraHistory& history = path.history;
                const int k = history.surfaces;
                const float longer = longerLightSubpaths(history, emitterLightArea(path.previousCosine, pointPdf, lightPdf),
                                                         [&] { return history.at(k).reverse; }, 0);
                weight = 1.0f / (1.0f + mis(lightPdf / path.previousPdf) * (1.0f + longer));
            }
        }
        path.deposit(depth, path.throughput * material.emission * weight);
    }
    if (depth >= maxBounces_) {
        if (depth == 0) out.albedo = tracer_.albedoAt(hit);
        path.done = true;
        return;
    }
    // The BSDF's frame first, then the delta lights' shadow rays; the albedo is read in the
    // next stage.
    path.bsdf.emplace(material, -direction, hit.geometricNormal, hit.shadingNormal, hit.frontFace);
    if (path.diffuseOnly) path.bsdf->keepDiffuseLobeOnly();
    path.deltas.visible = 0;
    if (path.bsdf->hasSmoothPart()) deltaShadows(*path.bsdf, hit, path.uDisc, path.deltas, out.rays);
}

void Integrator::leaveSurface(PathState& path) const {
    PathSample& out = path.out;
    const int depth = path.depth;
    const RayHit& hit = path.hit;
    Bsdf& bsdf = *path.bsdf;
    CameraHistory& history = path.history;
    const Material& material = scene_.materials[hit.material];
    const glm::vec3 albedo = tracer_.albedoAt(hit);
    if (depth == 0) out.albedo = albedo;
    bsdf.setAlbedo(material, albedo);
    if (path.lightVertices) {
        const int k = depth + 1;
        const float cosine = std::abs(glm::dot(hit.geometricNormal, path.direction));
        history.surfaces = k;
        CameraHistory::Surface& here = history.at(k);
        here.arrival = k >= 2 && !path.previousDelta ? path.previousPdf * cosine / (hit.t * hit.t) : 0.0f;
        here.toPreviousArea = k >= 2 ? path.previousCosine / (hit.t * hit.t) : 0.0f;
        here.reverse = 0.0f;
    }
    if (bsdf.hasSmoothPart()) {
        path.deposit(depth + 1, path.throughput * sampleLights(bsdf, hit, path.uLight, path.uDisc, path.deltas,
                                                               path.lightVertices ? &history : nullptr, out.rays));
        if (path.lightVertices)
            connect(bsdf, hit, *path.lightVertices, path.uConnect, history,
                    [&](int scatterings, glm::vec3 c) { path.deposit(scatterings, path.throughput * c); }, out.rays);
    }

    path.done = true;  // until the path survives this bounce
    BsdfSample s;
    if (!bsdf.sample(path.uBsdf, s)) return;
    // Without caustics, every surface after one that scatters diffusely keeps only its diffuse
    // lobe: light that reaches a diffuse surface by a specular reflection or a refraction is
    // left out (the path tracer then traces no light subpaths, PathTracer::Impl).
    if (!caustics_ && bsdf.hasDiffuseLobe()) path.diffuseOnly = true;
    path.throughput *= s.weight;
    out.scatterings = depth + 1;
    path.previousPdf = s.pdf;
    path.previousDelta = s.delta;
    path.previousPosition = hit.position;
    if (path.lightVertices) {
        // A light subpath going on from here to the previous surface: what it would sample.
        // The MIS sums read it from the third surface on (no strategy joins the camera).
        CameraHistory::Surface& here = history.at(depth + 1);
        here.reverse = s.delta || depth < 2 ? 0.0f : reverseArea(bsdf, s.direction, history);
        path.previousCosine = std::abs(glm::dot(hit.geometricNormal, s.direction));
    }
    path.radianceScale *= s.radianceScale;
    if (depth >= 2) {
        // Russian roulette keeps the estimate unbiased: survivors carry 1 / q. Survival
        // follows the throughput (without the radiance scaling of refractions, which undoes
        // itself on the way out), so weights stay at 1 even for albedo 0.99 and paths that
        // lose no energy are never cut; kBounceGuard ends those. From the third surface on:
        // from the fourth, Sponza's equal-time RMSE was 16 % higher, the Cornell box's 10 %
        // and Sibenik's 7 %; from the second, Sponza's relMSE and HDR-FLIP rose
        // (docs/reference.md, "Roulette from the third surface").
        const std::uint32_t decision = bounceDecision(depth);
        float q = maxComponent(path.throughput) / path.radianceScale;
        if (q < 1.0f) {
            if (!(path.sampler.get1D(decision + 2) < q)) return;
            path.throughput /= q;
        }
    }
    if (maxComponent(path.throughput) <= 0.0f) return;
    path.origin = leavingPoint(hit, s.direction, sceneScale_);
    path.direction = s.direction;
    path.depth = depth + 1;
    path.done = false;
}

}  // namespace voxgi::pt
