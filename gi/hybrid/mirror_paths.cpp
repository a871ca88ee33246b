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

// The surface at a hit as the path tracer's Bsdf orients it: normals on the side of `wo`.
struct Oriented {
    glm::vec3 geometric, shading;
};
Oriented orient(const RayHit& hit, glm::vec3 wo) {
    Oriented o;
    o.geometric = glm::dot(hit.geometricNormal, wo) < 0.0f ? -hit.geometricNormal : hit.geometricNormal;
    o.shading = glm::dot(hit.shadingNormal, o.geometric) < 0.0f ? -hit.shadingNormal : hit.shadingNormal;
    return o;
}

// The mirror-like lobes of the material at `hit` seen from `wo` (at most a reflection and a
// refraction), with the weights of the path tracer's material (gi/pathtrace/bsdf.h): the
// opaque part's coat or metal by Schlick's Fresnel at the clamped alpha (a mirror to within
// its Smith term), the smooth dielectric's reflection and refraction by the exact Fresnel
// term, refraction tinted by the albedo and scaled by eta^2 (radiance squeezed into the denser
// medium). Directions that land on the wrong geometric side are dropped, as the path tracer does.
int mirrorLobes(const Material& m, glm::vec3 albedo, const RayHit& hit, glm::vec3 wo, Lobe out[2]) {
    if (!shading::smoothLobe(m.roughness)) return 0;
    const Oriented o = orient(hit, wo);
    const float cosine = glm::dot(o.shading, wo);
    if (!(cosine > 0.0f)) return 0;
    const float t = std::clamp(m.transmission, 0.0f, 1.0f);
    const glm::vec3 f0 = coatF0(m, albedo);
    glm::vec3 reflect(0.0f);
    if (t < 1.0f && maxComponent(f0) > 0.0f) reflect += (1.0f - t) * pt::fresnelSchlick(f0, cosine);
    int n = 0;
    if (t > 0.0f) {
        const float eta = hit.frontFace ? 1.0f / m.ior : m.ior;
        const float F = pt::fresnelDielectric(cosine, eta);
        reflect += glm::vec3(t * F);
        const float sin2t = eta * eta * (1.0f - cosine * cosine);
        if (sin2t < 1.0f && F < 1.0f) {
            const glm::vec3 d = glm::normalize(-eta * wo + (eta * cosine - std::sqrt(1.0f - sin2t)) * o.shading);
            if (glm::dot(o.geometric, d) < 0.0f) out[n++] = {d, t * (1.0f - F) * albedo * (eta * eta)};
        }
    }
    const glm::vec3 r = 2.0f * cosine * o.shading - wo;
    if (maxComponent(reflect) > 0.0f && glm::dot(o.geometric, r) > 0.0f) out[n++] = {r, reflect};
    return n;
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

}  // namespace

bool tracesMirrorLobe(const shading::GBufferSurface& s) {
    return shading::hasMirrorLobe(s.roughness, s.metallic, s.specular, s.transmission);
}

MirrorPaths traceMirrorPaths(const RayTracer& tracer, const MirrorPathInput& in) {
    const Scene& scene = tracer.scene();
    const float offsetScale = pt::rayOffsetScale(scene);
    const int maxSlots = 2 * std::max(in.depth, 1);
    MirrorPaths out;
    out.width = in.width;
    out.height = in.height;
    const std::size_t count = std::size_t(in.width) * std::size_t(in.height);
    out.emittedDirect.assign(count, glm::vec4(0.0f));
    out.emittedIndirect.assign(count, glm::vec4(0.0f));
    std::vector<std::vector<Found>> rows(std::size_t(std::max(in.height, 0)));
    std::atomic<std::uint64_t> rays{0};
    std::atomic<std::size_t> pixels{0};

    tbb::parallel_for(0, in.height, [&](int y) {
        std::uint64_t rowRays = 0;
        std::size_t rowPixels = 0;
        for (int x = 0; x < in.width; ++x) {
            const std::size_t i = std::size_t(y) * std::size_t(in.width) + std::size_t(x);
            auto texel = [&](const float* p) { return glm::vec4(p[4 * i], p[4 * i + 1], p[4 * i + 2], p[4 * i + 3]); };
            const shading::GBufferTexels t{texel(in.position), texel(in.normal), texel(in.albedo), texel(in.emission)};
            if (!shading::gbufferHit(t.position) || !tracesMirrorLobe(shading::decodeGBuffer(t))) continue;
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
            Lobe lobes[2];
            const int branches = mirrorLobes(pm, tracer.albedoAt(primary), primary, -view, lobes);
            if (branches == 0) continue;
            ++rowPixels;
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
                    if (hit.frontFace && m.isEmissive()) emitted[i] += glm::vec4(weight * m.emission, 0.0f);
                    if (slot < maxSlots && shadeable(m, albedo)) {
                        const Oriented o = orient(hit, -direction);
                        shading::GBufferSurface s;
                        s.position = hit.position;
                        s.normal = o.shading;
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
                    const int n = mirrorLobes(m, albedo, hit, -direction, next);
                    if (n == 0) break;
                    // Past the pixel's own surface one lobe is followed, chosen in proportion to
                    // its weight's luminance (the frames average the choices).
                    int pick = 0;
                    float probability = 1.0f;
                    if (n == 2) {
                        const float l0 = shading::luminanceRec709(next[0].weight), l1 = shading::luminanceRec709(next[1].weight);
                        const float p0 = l0 + l1 > 0.0f ? l0 / (l0 + l1) : 0.5f;
                        const std::uint32_t key =
                            hash32(std::uint32_t(i) ^ hash32(in.frame * 16u + std::uint32_t(b * 8 + vertex)));
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
    });

    int layers = 0;
    for (const auto& row : rows)
        for (const Found& f : row) layers = std::max(layers, f.slot + 1);
    out.layers.resize(std::size_t(layers));
    for (SecondaryLayer& l : out.layers) {
        l.texels.assign(count, shading::GBufferTexels{glm::vec4(0.0f), glm::vec4(0.0f), glm::vec4(0.0f), glm::vec4(0.0f)});
        l.viewOrigin.assign(count, glm::vec4(0.0f));
        l.weight.assign(count, glm::vec4(0.0f));
    }
    std::vector<glm::ivec4> box(out.layers.size(), glm::ivec4(in.width, in.height, -1, -1));  // x0 y0 x1 y1, inclusive
    for (const auto& row : rows)
        for (const Found& f : row) {
            SecondaryLayer& l = out.layers[std::size_t(f.slot)];
            const glm::ivec2 p(int(f.pixel % std::size_t(in.width)), int(f.pixel / std::size_t(in.width)));
            glm::ivec4& b = box[std::size_t(f.slot)];
            b = glm::ivec4(glm::min(glm::ivec2(b), p), glm::max(glm::ivec2(b.z, b.w), p));
            l.texels[f.pixel] = f.texels;
            l.viewOrigin[f.pixel] = glm::vec4(f.viewOrigin, 1.0f);
            l.weight[f.pixel] = glm::vec4(f.weight, 1.0f);
        }
    for (std::size_t l = 0; l < out.layers.size(); ++l)
        out.layers[l].bounds = glm::ivec4(box[l].x, box[l].y, box[l].z - box[l].x + 1, box[l].w - box[l].y + 1);
    out.rays = rays;
    out.pixels = pixels;
    return out;
}

}  // namespace voxgi
