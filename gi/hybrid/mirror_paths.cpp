#include "gi/hybrid/mirror_paths.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#include <tbb/parallel_for.h>

#include "gi/pathtrace/bsdf.h"
#include "gi/pathtrace/integrator.h"
#include "gi/raytrace/ray_tracer.h"
#include "gi/sampling/hash.h"
#include "shaders/shared/color.h"

namespace voxgi {

namespace {

float maxComponent(glm::vec3 v) { return std::max(v.x, std::max(v.y, v.z)); }

glm::vec3 coatF0(const Material& m, glm::vec3 albedo) { return glm::mix(glm::vec3(m.specular), albedo, m.metallic); }

// A mirror-like lobe leaving a surface: its direction and what it multiplies the light by.
struct Lobe {
    glm::vec3 direction{0.0f};
    glm::vec3 weight{0.0f};
};

// The mirror-like lobes of the material at a hit, `bsdf` there seen from `wo` (at most a
// reflection and a refraction), with the path tracer's weights: the opaque part's coat or metal
// by Schlick's Fresnel at the clamped alpha (a mirror to within its Smith term), and the smooth
// dielectric's delta pair as its own sampling gives them (gi/pathtrace/bsdf.h: exact Fresnel,
// refraction tinted and scaled by eta^2, directions on the wrong geometric side dropped), each
// sample's weight times its probability.
int mirrorLobes(const Material& m, glm::vec3 albedo, const pt::Bsdf& bsdf, glm::vec3 wo, Lobe out[2]) {
    if (!shading::smoothLobe(m.roughness)) return 0;
    const glm::vec3 n = bsdf.shadingNormal(), ng = bsdf.geometricNormal();
    const float cosine = glm::dot(n, wo);
    if (!(cosine > 0.0f)) return 0;
    const float t = std::clamp(m.transmission, 0.0f, 1.0f);
    const glm::vec3 f0 = coatF0(m, albedo);
    glm::vec3 reflect(0.0f);
    if (t < 1.0f && maxComponent(f0) > 0.0f) reflect += (1.0f - t) * pt::fresnelSchlick(f0, cosine);
    int count = 0;
    if (t > 0.0f) {
        // u.z = 0 picks the dielectric; u.x below F reflects, above refracts (at total internal
        // reflection the second sample reflects again and is not counted twice).
        for (const float choose : {0.0f, 0.99999994f}) {
            pt::BsdfSample s;
            if (!bsdf.sample(glm::vec3(choose, 0.0f, 0.0f), s) || !s.delta) continue;
            const bool reflected = glm::dot(ng, s.direction) > 0.0f;
            if (!reflected) out[count++] = {s.direction, s.weight * s.pdf};
            else if (choose == 0.0f) reflect += s.weight * s.pdf;
        }
    }
    const glm::vec3 r = 2.0f * cosine * n - wo;
    if (maxComponent(reflect) > 0.0f && glm::dot(ng, r) > 0.0f) out[count++] = {r, reflect};
    return count;
}

// Whether the frame's passes have anything to shade at this surface besides its mirror-like
// lobes: a diffuse lobe, or a GGX lobe too rough to trace. (A rough dielectric's transmission
// is neither: the rasterized passes leave it out, and so does the hybrid method.)
bool shadeable(const Material& m, glm::vec3 albedo) {
    if (maxComponent(shading::diffuseAlbedo(albedo, m.metallic, m.specular, m.transmission)) > 0.0f) return true;
    return !shading::smoothLobe(m.roughness) && m.transmission < 1.0f && maxComponent(coatF0(m, albedo)) > 0.0f;
}

// A shadeable surface found by one pixel's rays, before the layers are laid out.
struct Found {
    std::size_t pixel;
    int slot;
    shading::GBufferTexels texels;
    glm::vec3 viewOrigin, weight;
};

// Per material: whether it is the geometry of one of the scene's quad lights, which the
// rasterized direct pass samples itself (Scene::addQuadLightGeometry).
std::vector<bool> quadLightMaterials(const Scene& scene) {
    std::vector<bool> out(scene.materials.size(), false);
    for (std::size_t l = 0; l < scene.lights.size(); ++l)
        if (const Mesh* mesh = scene.quadLightMesh(l))
            for (const std::uint32_t m : mesh->materialIds)
                if (m < out.size()) out[m] = true;
    return out;
}

}  // namespace

bool tracesMirrorLobe(const shading::GBufferSurface& s) {
    return shading::hasMirrorLobe(s.roughness, s.metallic, s.specular, s.transmission);
}

MirrorPaths traceMirrorPaths(const RayTracer& tracer, const MirrorPathInput& in) {
    const Scene& scene = tracer.scene();
    const float offsetScale = pt::rayOffsetScale(scene);
    const int glossyRays = std::clamp(in.glossyRays, 1, kMaxGlossyRays);
    const int maxSlots = std::max(2, glossyRays) * std::max(in.depth, 1);
    const std::vector<bool> quadLight = quadLightMaterials(scene);
    MirrorPaths out;
    out.width = in.width;
    out.height = in.height;
    const std::size_t count = std::size_t(in.width) * std::size_t(in.height);
    out.emittedDirect.assign(count, glm::vec4(0.0f));
    out.emittedIndirect.assign(count, glm::vec4(0.0f));
    std::vector<std::vector<Found>> rows(std::size_t(std::max(in.height, 0)));
    // Per row, the first and last pixel traced (x0 > x1: none).
    std::vector<glm::ivec2> tracedSpan(rows.size(), glm::ivec2(in.width, -1));
    std::atomic<std::uint64_t> rays{0};
    std::atomic<std::size_t> pixels{0}, glossyPixels{0};

    tbb::parallel_for(0, in.height, [&](int y) {
        std::uint64_t rowRays = 0;
        std::size_t rowPixels = 0, rowGlossy = 0;
        for (int x = 0; x < in.width; ++x) {
            const std::size_t i = std::size_t(y) * std::size_t(in.width) + std::size_t(x);
            auto texel = [&](const float* p) { return glm::vec4(p[4 * i], p[4 * i + 1], p[4 * i + 2], p[4 * i + 3]); };
            const shading::GBufferTexels t{texel(in.position), texel(in.normal), texel(in.albedo), texel(in.emission)};
            if (!shading::gbufferHit(t.position)) continue;
            // The G-buffer decides which pixels are traced, as the rasterized passes decide which
            // lobes they leave to the rays (shading::tracedLobe on the same values).
            const shading::GBufferSurface gs = shading::decodeGBuffer(t);
            const bool glossy = shading::glossyLobe(gs.roughness, gs.metallic, gs.specular, gs.transmission,
                                                    in.glossyRoughness);
            if (!glossy && !tracesMirrorLobe(gs)) continue;
            glm::ivec2& span = tracedSpan[std::size_t(y)];
            span = glm::ivec2(std::min(span.x, x), std::max(span.y, x));
            // The pixel's surface again, with Embree: its exact material, sides and normals.
            const glm::vec3 toSurface = glm::vec3(t.position) - in.eye;
            const float distance = glm::length(toSurface);
            if (!(distance > 0.0f)) continue;
            const glm::vec3 view = toSurface / distance;
            const RayHit primary = tracer.intersect(in.eye, view);
            ++rowRays;
            // At silhouettes the rasterizer and Embree can see different surfaces: then the
            // pixel keeps what the rasterizer shaded.
            if (!primary.hit || std::abs(primary.t - distance) > 1e-3f * distance + 1e-5f * offsetScale) continue;
            const Material& pm = scene.materials[primary.material];
            const glm::vec3 primaryAlbedo = tracer.albedoAt(primary);
            const pt::Bsdf primaryBsdf(pm, primaryAlbedo, -view, primary.geometricNormal, primary.shadingNormal,
                                       primary.frontFace);
            Lobe lobes[std::max(2, kMaxGlossyRays)];
            int branches = 0;
            if (glossy) {
                // Rays sampled from the GGX lobe, each weighted f cos / (pdf N): the frames average
                // the directions.
                for (int r = 0; r < glossyRays; ++r) {
                    const std::uint32_t key = hash32(std::uint32_t(i) ^ hash32(in.frame * std::uint32_t(kMaxGlossyRays) +
                                                                               std::uint32_t(r)));
                    const glm::vec2 u(float(key >> 8) * (1.0f / 16777216.0f),
                                      float(hash32(key) >> 8) * (1.0f / 16777216.0f));
                    pt::BsdfSample sample;
                    if (primaryBsdf.sampleGlossy(u, sample))
                        lobes[branches++] = {sample.direction, sample.weight / float(glossyRays)};
                }
                ++rowGlossy;
            } else {
                branches = mirrorLobes(pm, primaryAlbedo, primaryBsdf, -view, lobes);
                if (branches > 0) ++rowPixels;
            }
            if (branches == 0) continue;
            int slot = 0;
            for (int b = 0; b < branches; ++b) {
                RayHit from = primary;
                glm::vec3 direction = lobes[b].direction, weight = lobes[b].weight;
                for (int vertex = 1; vertex <= in.depth; ++vertex) {
                    const glm::vec3 origin = pt::leavingPoint(from, direction, offsetScale);
                    const RayHit hit = tracer.intersect(origin, direction);
                    ++rowRays;
                    std::vector<glm::vec4>& emitted = vertex == 1 ? out.emittedDirect : out.emittedIndirect;
                    if (!hit.hit) {
                        emitted[i] += glm::vec4(weight * scene.sky.radianceAt(direction), 0.0f);
                        break;
                    }
                    const Material& m = scene.materials[hit.material];
                    const glm::vec3 albedo = tracer.albedoAt(hit);
                    // A glossy lobe's highlight of a quad light is the rasterized pass's (it samples
                    // the quad, with far less noise than rays that must hit it); rays bring
                    // everything else, and a mirror's reflection of the quad.
                    const bool sampledByRasterizer = glossy && vertex == 1 && quadLight[hit.material];
                    if (hit.frontFace && m.isEmissive() && !sampledByRasterizer)
                        emitted[i] += glm::vec4(weight * m.emission, 0.0f);
                    // The surface as the path tracer orients it: normals on the side the ray came from.
                    const pt::Bsdf bsdf(m, albedo, -direction, hit.geometricNormal, hit.shadingNormal, hit.frontFace);
                    if (slot < maxSlots && shadeable(m, albedo)) {
                        shading::GBufferSurface s;
                        s.position = hit.position;
                        s.normal = bsdf.shadingNormal();
                        s.albedo = albedo;
                        s.emission = glm::vec3(0.0f);  // added above, with the path's weight
                        s.roughness = m.roughness;
                        s.metallic = m.metallic;
                        s.specular = m.specular;
                        s.transmission = std::clamp(m.transmission, 0.0f, 1.0f);
                        rows[std::size_t(y)].push_back({i, slot++, shading::encodeGBuffer(s), origin, weight});
                    }
                    if (vertex == in.depth) break;
                    Lobe next[2];
                    const int n = mirrorLobes(m, albedo, bsdf, -direction, next);
                    if (n == 0) break;
                    // Past the pixel's own surface one lobe is followed, chosen in proportion to
                    // its weight's luminance (the frames average the choices).
                    int pick = 0;
                    float probability = 1.0f;
                    if (n == 2) {
                        const float l0 = shading::luminanceRec709(next[0].weight), l1 = shading::luminanceRec709(next[1].weight);
                        const float p0 = l0 + l1 > 0.0f ? l0 / (l0 + l1) : 0.5f;
                        const std::uint32_t key =
                            hash32(std::uint32_t(i) ^ hash32(in.frame * 256u + std::uint32_t(b * 8 + vertex)));
                        const float u = float(key >> 8) * (1.0f / 16777216.0f);
                        pick = u < p0 ? 0 : 1;
                        probability = pick == 0 ? p0 : 1.0f - p0;
                    }
                    weight *= next[pick].weight / probability;
                    direction = next[pick].direction;
                    from = hit;
                }
            }
        }
        rays += rowRays;
        pixels += rowPixels;
        glossyPixels += rowGlossy;
    });

    int layers = 0;
    for (const auto& row : rows)
        for (const Found& f : row) layers = std::max(layers, f.slot + 1);
    out.layers.resize(std::size_t(layers));
    for (SecondaryLayer& l : out.layers)
        for (std::vector<glm::vec4>* v : {&l.position, &l.normal, &l.albedo, &l.emission, &l.viewOrigin, &l.weight})
            v->assign(count, glm::vec4(0.0f));
    std::vector<glm::ivec4> box(out.layers.size(), glm::ivec4(in.width, in.height, -1, -1));  // x0 y0 x1 y1, inclusive
    for (const auto& row : rows)
        for (const Found& f : row) {
            SecondaryLayer& l = out.layers[std::size_t(f.slot)];
            const glm::ivec2 p(int(f.pixel % std::size_t(in.width)), int(f.pixel / std::size_t(in.width)));
            glm::ivec4& b = box[std::size_t(f.slot)];
            b = glm::ivec4(glm::min(glm::ivec2(b), p), glm::max(glm::ivec2(b.z, b.w), p));
            l.position[f.pixel] = f.texels.position;
            l.normal[f.pixel] = f.texels.normal;
            l.albedo[f.pixel] = f.texels.albedo;
            l.emission[f.pixel] = f.texels.emission;
            l.viewOrigin[f.pixel] = glm::vec4(f.viewOrigin, 1.0f);
            l.weight[f.pixel] = glm::vec4(f.weight, 1.0f);
        }
    for (std::size_t l = 0; l < out.layers.size(); ++l)
        out.layers[l].bounds = glm::ivec4(box[l].x, box[l].y, box[l].z - box[l].x + 1, box[l].w - box[l].y + 1);
    glm::ivec4 traced(in.width, in.height, -1, -1);
    for (int y = 0; y < in.height; ++y) {
        const glm::ivec2 span = tracedSpan[std::size_t(y)];
        if (span.x > span.y) continue;
        traced = glm::ivec4(std::min(traced.x, span.x), std::min(traced.y, y), std::max(traced.z, span.y), std::max(traced.w, y));
    }
    out.emittedBounds = glm::ivec4(traced.x, traced.y, traced.z - traced.x + 1, traced.w - traced.y + 1);
    out.rays = rays;
    out.pixels = pixels;
    out.glossyPixels = glossyPixels;
    return out;
}

}  // namespace voxgi
