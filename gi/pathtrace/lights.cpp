#include "gi/pathtrace/lights.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>

#include "gi/pathtrace/bsdf.h"
#include "shaders/shared/color.h"
#include "shaders/shared/constants.h"

namespace voxgi::pt {

namespace {
using shading::luminanceRec709;

// Below this solid angle (sr) a rectangle is sampled by area too: the spherical mapping's
// cancellations (an angle excess of four angles near pi/2) lose precision there even in double,
// and from that far the two pdfs differ by far less than the noise.
constexpr double kMinSolidAngle = 1e-6;
// Float leaves the angle excess about 3e-7 sr wrong: below this solid angle the rectangle is
// set up again in double (1e-4 relative at most in float above it).
constexpr float kFloatSolidAngle = 3e-3f;

// The spherical rectangle of Urena et al. seen from the origin of the rectangle's frame: the
// rectangle spans [x0, x1] x [y0, y1] at depth z0 < 0 along its normal.
template <typename T>
struct SphericalRectangle {
    using V = glm::vec<3, T>;
    T x0, x1, y0, y1, z0;
    T b0, b1, k, solidAngle;

    SphericalRectangle(T x0_, T x1_, T y0_, T y1_, T z0_) : x0(x0_), x1(x1_), y0(y0_), y1(y1_), z0(z0_) {
        // Normals of the four planes through the origin and an edge, in the rectangle's frame.
        const V n0 = glm::normalize(V(0, z0, -y0));
        const V n1 = glm::normalize(V(-z0, 0, x1));
        const V n2 = glm::normalize(V(0, -z0, y1));
        const V n3 = glm::normalize(V(z0, 0, -x0));
        auto angle = [](V a, V b) { return std::acos(std::clamp(-glm::dot(a, b), T(-1), T(1))); };
        const T g0 = angle(n0, n1), g1 = angle(n1, n2), g2 = angle(n2, n3), g3 = angle(n3, n0);
        b0 = n0.z;
        b1 = n2.z;
        k = T(2.0 * shading::kPiDouble) - g2 - g3;
        solidAngle = g0 + g1 - k;  // the spherical quadrilateral's angle excess
    }

    // The point (x, y) of the rectangle's plane for u in [0, 1)^2.
    glm::dvec2 sample(glm::vec2 u) const {
        const T au = T(u.x) * solidAngle + k;
        const T fu = (std::cos(au) * b0 - b1) / std::sin(au);
        T cu = std::copysign(T(1), fu) / std::sqrt(fu * fu + b0 * b0);
        cu = std::clamp(cu, T(-1), T(1));
        const T xu = std::clamp(-(cu * z0) / std::sqrt(std::max(T(1) - cu * cu, T(1e-30))), x0, x1);
        const T d2 = xu * xu + z0 * z0;
        const T h0 = y0 / std::sqrt(d2 + y0 * y0), h1 = y1 / std::sqrt(d2 + y1 * y1);
        const T hv = h0 + T(u.y) * (h1 - h0), hv2 = hv * hv;
        const T yv = hv2 < T(1) - T(1e-6) ? std::clamp(hv * std::sqrt(d2) / std::sqrt(T(1) - hv2), y0, y1) : y1;
        return {double(xu), double(yv)};
    }
};

// The rectangle seen from p, in float where float is precise enough, else in double; nullopt
// when p is behind (or in) its emitting plane. Sampling and pdf both go through here, so they
// always agree on the precision and on the switch to area sampling.
struct RectangleView {
    double solidAngle = 0.0;
    double x0 = 0.0, y0 = 0.0;
    std::optional<SphericalRectangle<float>> single;
    std::optional<SphericalRectangle<double>> precise;
    glm::dvec2 sample(glm::vec2 u) const { return single ? single->sample(u) : precise->sample(u); }
};

// Seen from farther than this many diagonals the rectangle is sampled by area: 1/r^2 and the
// cosines vary by less than +-20 % over it, so solid-angle sampling would remove little noise
// for its trigonometry (in Sibenik, whose nave light is far from most points, 13 % of the time).
constexpr float kSphericalWithin = 5.0f;

template <typename Rect>
bool view(const Rect& r, glm::vec3 p, RectangleView& out) {
    const glm::vec3 d = r.corner - p;
    const float z0 = glm::dot(d, r.normal);
    if (!(z0 < 0.0f)) return false;
    const glm::vec3 toCentre = d + 0.5f * (r.width * r.ex + r.height * r.ey);
    if (glm::dot(toCentre, toCentre) > kSphericalWithin * kSphericalWithin * (r.width * r.width + r.height * r.height)) {
        out.solidAngle = 0.0;  // area sampling
        return true;
    }
    const float x0 = glm::dot(d, r.ex), y0 = glm::dot(d, r.ey);
    out.single.emplace(x0, x0 + r.width, y0, y0 + r.height, z0);
    out.x0 = x0;
    out.y0 = y0;
    out.solidAngle = out.single->solidAngle;
    if (out.single->solidAngle < kFloatSolidAngle) {
        out.single.reset();
        const glm::dvec3 dd = glm::dvec3(r.corner) - glm::dvec3(p);
        const double dz = glm::dot(dd, glm::dvec3(r.normal));
        if (!(dz < 0.0)) return false;
        const double dx = glm::dot(dd, glm::dvec3(r.ex)), dy = glm::dot(dd, glm::dvec3(r.ey));
        out.precise.emplace(dx, dx + r.width, dy, dy + r.height, dz);
        out.x0 = dx;
        out.y0 = dy;
        out.solidAngle = out.precise->solidAngle;
    }
    return true;
}
}  // namespace

LightSampler::LightSampler(const Scene& scene) {
    for (const Light& l : scene.lights)
        if (l.type != LightType::Quad) deltas_.push_back(shading::packLight(l));  // quads are emissive geometry
    for (const shading::PackedLight& l : deltas_)
        sunDisc_ = sunDisc_ || (l.kind.x == shading::kLightDirectional && l.shape.w > 0.0f);

    std::vector<double> emitted;
    for (const shading::PackedLight& l : deltas_) {
        double measure = 4.0 * shading::kPiDouble;  // point: the sphere
        if (l.kind.x == shading::kLightSpot) measure = 2.0 * shading::kPiDouble * (1.0 - double(l.shape.x));
        if (l.kind.x == shading::kLightDirectional) measure = 0.0;
        emitted.push_back(std::max(double(luminanceRec709(glm::vec3(l.emission))), 0.0) * std::max(measure, 0.0));
    }
    const double emittedTotal = std::accumulate(emitted.begin(), emitted.end(), 0.0);

    std::vector<double> power;
    meshRectangle_.assign(scene.meshes.size(), -1);
    for (std::size_t i = 0; i < scene.lights.size(); ++i) {
        const Light& l = scene.lights[i];
        if (l.type != LightType::Quad) continue;
        const float w = glm::length(l.edgeU), h = glm::length(l.edgeV);
        // Parallelograms that are not rectangles keep per-triangle area sampling.
        if (!(w > 0.0f && h > 0.0f) || std::abs(glm::dot(l.edgeU, l.edgeV)) > 1e-4f * w * h) continue;
        const Mesh* mesh = scene.quadLightMesh(i);
        if (!mesh || luminanceRec709(l.emission) <= 0.0f) continue;
        meshRectangle_[std::size_t(mesh - scene.meshes.data())] = std::int32_t(rectangles_.size());
        rectangles_.push_back({l.position, l.edgeU / w, l.edgeV / h, l.quadNormal(), w, h, l.emission});
        emitters_.push_back({true, std::uint32_t(rectangles_.size() - 1), 0.0f});
        power.push_back(double(w) * double(h) * double(luminanceRec709(l.emission)));
    }

    std::size_t global = 0;
    std::vector<std::size_t> triangleGlobal;
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
        const Mesh& mesh = scene.meshes[m];
        meshFirstTriangle_.push_back(global);
        for (std::size_t t = 0; t < mesh.triangleCount(); ++t, ++global) {
            const Material& material = scene.materials[mesh.materialIds[t]];
            if (meshRectangle_[m] >= 0 || !material.isEmissive()) continue;
            glm::vec3 a = mesh.positions[mesh.indices[3 * t]];
            glm::vec3 b = mesh.positions[mesh.indices[3 * t + 1]];
            glm::vec3 c = mesh.positions[mesh.indices[3 * t + 2]];
            glm::vec3 cr = glm::cross(b - a, c - a);
            float area = 0.5f * glm::length(cr);
            if (!(area > 0.0f) || !std::isfinite(area)) continue;
            triangles_.push_back({a, b - a, c - a, glm::normalize(cr), material.emission, area});
            emitters_.push_back({false, std::uint32_t(triangles_.size() - 1), 0.0f});
            power.push_back(double(area) * double(std::max(luminanceRec709(material.emission), 1e-6f)));
            triangleGlobal.push_back(global);
        }
    }
    trianglePdfArea_.assign(global, 0.0f);
    rectangleProbability_.assign(rectangles_.size(), 0.0f);
    double total = 0.0;
    for (double p : power) total += p;
    double running = 0.0;
    for (std::size_t i = 0; i < emitters_.size(); ++i) {
        running += power[i];
        cdf_.push_back(float(running / total));
        Emitter& e = emitters_[i];
        e.probability = float(power[i] / total);
        if (e.rectangle)
            rectangleProbability_[e.index] = e.probability;
        else
            trianglePdfArea_[triangleGlobal[e.index]] = e.probability / triangles_[e.index].area;
    }
    if (!cdf_.empty()) cdf_.back() = 1.0f;

    // Light subpaths: deltas and emitters in proportion to the power they send out (a
    // Lambertian emitter's is pi x radiance x area).
    const double emitterPower = cdf_.empty() || !std::isfinite(total) ? 0.0 : shading::kPiDouble * total;
    const double all = (emittedTotal > 0.0 && std::isfinite(emittedTotal) ? emittedTotal : 0.0) + emitterPower;
    if (!(all > 0.0)) return;
    emitterRayShare_ = float(emitterPower / all);
    if (emittedTotal > 0.0 && std::isfinite(emittedTotal)) {
        double running = 0.0;
        for (double p : emitted) {
            running += p;
            rayProbability_.push_back(float(p / all));
            rayCdf_.push_back(float(running / emittedTotal));
        }
        rayCdf_.back() = 1.0f;
    }
}

LightSample LightSampler::sampleDelta(std::size_t index, glm::vec3 p, glm::vec2 u) const {
    // Deltas are never quads: u picks a direction of a sun's disc only.
    const shading::IncidentLight incident = shading::evaluateLight(deltas_[index], p, u);
    LightSample s;
    s.direction = incident.direction;
    s.distance = incident.distance;
    s.radiance = incident.irradiance;
    return s;
}

float LightSampler::emissionPdf(std::size_t index) const {
    const shading::PackedLight& l = deltas_[index];
    if (l.kind.x == shading::kLightSpot) return rayProbability_[index] / (2.0f * shading::kPi * (1.0f - l.shape.x));
    return rayProbability_[index] / (4.0f * shading::kPi);
}

EmittedRay LightSampler::sampleEmission(glm::vec3 u, glm::vec2 uPoint) const {
    EmittedRay ray;
    const float deltaShare = 1.0f - emitterRayShare_;
    if (u.z >= deltaShare || rayCdf_.empty()) {
        if (!(emitterRayShare_ > 0.0f)) return ray;
        const std::size_t i = pickEmitter(std::clamp((u.z - deltaShare) / emitterRayShare_, 0.0f, 0.99999994f));
        const Emitter& e = emitters_[i];
        glm::vec3 emission;
        if (e.rectangle) {
            const Rectangle& r = rectangles_[e.index];
            ray.origin = r.corner + uPoint.x * r.width * r.ex + uPoint.y * r.height * r.ey;
            ray.normal = r.normal;
            emission = r.emission;
        } else {
            const Triangle& t = triangles_[e.index];
            const float su = std::sqrt(uPoint.x);
            ray.origin = t.a + (1.0f - uPoint.y) * su * t.e1 + uPoint.y * su * t.e2;
            ray.normal = t.normal;
            emission = t.emission;
        }
        // Cosine-weighted about the emitting side.
        const float r = std::sqrt(u.x), phi = 2.0f * shading::kPi * u.y;
        const float cosine = std::sqrt(std::max(0.0f, 1.0f - u.x));
        glm::vec3 tx, ty;
        orthonormalBasis(ray.normal, tx, ty);
        ray.direction = glm::normalize(r * std::cos(phi) * tx + r * std::sin(phi) * ty + cosine * ray.normal);
        ray.pdf = emissionPointPdf(e) * cosine / shading::kPi;
        ray.intensity = emission * cosine;
        ray.emitter = std::int32_t(i);
        if (!(ray.pdf > 0.0f) || !std::isfinite(ray.pdf)) return EmittedRay{};
        return ray;
    }
    const float select = std::min(u.z / deltaShare, 0.99999994f);
    const std::size_t i = std::min(std::size_t(std::lower_bound(rayCdf_.begin(), rayCdf_.end(), select) - rayCdf_.begin()),
                                   deltas_.size() - 1);
    if (!(rayProbability_[i] > 0.0f)) return ray;
    const shading::PackedLight& l = deltas_[i];
    const float phi = 2.0f * shading::kPi * u.y;
    ray.origin = glm::vec3(l.position);
    ray.intensity = glm::vec3(l.emission);
    ray.pdf = emissionPdf(i);
    if (l.kind.x == shading::kLightSpot) {
        const glm::vec3 axis = glm::vec3(l.direction);
        glm::vec3 t, b;
        orthonormalBasis(axis, t, b);
        const float cosT = 1.0f - u.x * (1.0f - l.shape.x), sinT = std::sqrt(std::max(0.0f, 1.0f - cosT * cosT));
        ray.direction = sinT * (std::cos(phi) * t + std::sin(phi) * b) + cosT * axis;
        ray.intensity *= shading::spotFalloff(l.shape.x, l.shape.y, cosT);
        return ray;
    }
    const float z = 1.0f - 2.0f * u.x, s = std::sqrt(std::max(0.0f, 1.0f - z * z));
    ray.direction = glm::vec3(s * std::cos(phi), s * std::sin(phi), z);
    return ray;
}

float LightSampler::emissionPointPdf(std::uint32_t mesh, std::uint32_t triangle) const {
    if (!(emitterRayShare_ > 0.0f)) return 0.0f;
    if (const std::int32_t r = meshRectangle_[mesh]; r >= 0) {
        const Rectangle& rect = rectangles_[std::size_t(r)];
        return emitterRayShare_ * rectangleProbability_[std::size_t(r)] / (rect.width * rect.height);
    }
    return emitterRayShare_ * trianglePdfArea_[meshFirstTriangle_[mesh] + triangle];
}

float LightSampler::emitterPdf(std::int32_t emitter, glm::vec3 from, glm::vec3 at, float cosLight) const {
    if (emitter < 0 || !(cosLight > 0.0f)) return 0.0f;
    const Emitter& e = emitters_[std::size_t(emitter)];
    if (e.rectangle) return e.probability * rectanglePdf(rectangles_[e.index], from, at, cosLight);
    const glm::vec3 to = at - from;
    return e.probability / area(e) * glm::dot(to, to) / cosLight;
}

float LightSampler::area(const Emitter& e) const {
    return e.rectangle ? rectangles_[e.index].width * rectangles_[e.index].height : triangles_[e.index].area;
}

float LightSampler::emissionPointPdf(const Emitter& e) const { return emitterRayShare_ * e.probability / area(e); }

std::size_t LightSampler::pickEmitter(float select) const {
    return std::min(std::size_t(std::lower_bound(cdf_.begin(), cdf_.end(), select) - cdf_.begin()), emitters_.size() - 1);
}

float LightSampler::emissionPdfArea(std::size_t index, glm::vec3 toLight, float distance, float cosAtY) const {
    if (rayProbability_.empty() || !(rayProbability_[index] > 0.0f)) return 0.0f;
    // The spot emits into its outer cone only.
    const shading::PackedLight& l = deltas_[index];
    if (l.kind.x == shading::kLightSpot && glm::dot(-toLight, glm::vec3(l.direction)) < l.shape.x) return 0.0f;
    return emissionPdf(index) * cosAtY / (distance * distance);
}

namespace {
// Fills direction and distance from p to q; false when q is p or lies behind the emitter.
bool aim(LightSample& s, glm::vec3 p, glm::vec3 q, glm::vec3 normal, float* cosLight) {
    glm::vec3 d = q - p;
    float d2 = glm::dot(d, d);
    if (!(d2 > 0.0f)) return false;
    s.distance = std::sqrt(d2);
    s.direction = d / s.distance;
    s.position = q;
    s.normal = normal;
    *cosLight = -glm::dot(normal, s.direction);
    return *cosLight > 0.0f;  // emitters shine from their front face only
}
}  // namespace

LightSample LightSampler::sampleTriangle(const Triangle& t, glm::vec3 p, glm::vec2 u) const {
    LightSample s;
    float su = std::sqrt(u.x);
    glm::vec3 q = t.a + (1.0f - u.y) * su * t.e1 + u.y * su * t.e2;
    float cosLight;
    if (!aim(s, p, q, t.normal, &cosLight)) return LightSample{};
    s.pdf = s.distance * s.distance / (cosLight * t.area);
    return s;
}

LightSample LightSampler::sampleRectangle(const Rectangle& r, glm::vec3 p, glm::vec2 u) const {
    RectangleView v;
    if (!view(r, p, v)) return LightSample{};
    LightSample s;
    float cosLight;
    if (v.solidAngle >= kMinSolidAngle) {
        // Rebuilt from the corner, so the point lies on the rectangle's plane to rounding.
        const glm::dvec2 local = v.sample(u);
        if (!aim(s, p, r.corner + float(local.x - v.x0) * r.ex + float(local.y - v.y0) * r.ey, r.normal, &cosLight))
            return LightSample{};
        s.pdf = float(1.0 / v.solidAngle);
    } else {
        if (!aim(s, p, r.corner + u.x * r.width * r.ex + u.y * r.height * r.ey, r.normal, &cosLight))
            return LightSample{};
        s.pdf = s.distance * s.distance / (cosLight * r.width * r.height);
    }
    return s;
}

LightSample LightSampler::sampleEmitter(glm::vec3 p, glm::vec2 u, float select) const {
    const Emitter& e = emitters_[pickEmitter(select)];
    LightSample s = e.rectangle ? sampleRectangle(rectangles_[e.index], p, u) : sampleTriangle(triangles_[e.index], p, u);
    if (!(s.pdf > 0.0f) || !std::isfinite(s.pdf)) return LightSample{};
    s.pdf *= e.probability;
    s.radiance = (e.rectangle ? rectangles_[e.index].emission : triangles_[e.index].emission) / s.pdf;
    s.lightPathPdfArea = emissionPointPdf(e);
    return s;
}

float LightSampler::rectanglePdf(const Rectangle& r, glm::vec3 from, glm::vec3 at, float cosLight) const {
    RectangleView v;
    if (!view(r, from, v)) return 0.0f;
    if (v.solidAngle >= kMinSolidAngle) return float(1.0 / v.solidAngle);
    const glm::vec3 to = at - from;
    return glm::dot(to, to) / (cosLight * r.width * r.height);
}

float LightSampler::emitterPdf(std::uint32_t mesh, std::uint32_t triangle, glm::vec3 from, glm::vec3 at,
                               float cosLight) const {
    if (!(cosLight > 0.0f)) return 0.0f;
    if (const std::int32_t r = meshRectangle_[mesh]; r >= 0)
        return rectangleProbability_[std::size_t(r)] * rectanglePdf(rectangles_[std::size_t(r)], from, at, cosLight);
    const float pdfArea = trianglePdfArea_[meshFirstTriangle_[mesh] + triangle];
    const glm::vec3 to = at - from;
    return pdfArea * glm::dot(to, to) / cosLight;
}

}  // namespace voxgi::pt
