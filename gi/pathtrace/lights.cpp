#include "gi/pathtrace/lights.h"

#include <algorithm>
#include <cmath>

namespace voxgi::pt {

namespace {
float luminance(glm::vec3 c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }
}  // namespace

LightSampler::LightSampler(const Scene& scene) {
    for (const Light& l : scene.lights)
        if (l.type != LightType::Quad) deltas_.push_back(shading::packLight(l));  // quads are emissive geometry

    std::size_t global = 0;
    std::vector<double> power;
    std::vector<std::size_t> globalIndex;
    for (const Mesh& mesh : scene.meshes) {
        meshFirstTriangle_.push_back(global);
        for (std::size_t t = 0; t < mesh.triangleCount(); ++t, ++global) {
            const Material& m = scene.materials[mesh.materialIds[t]];
            if (!m.isEmissive()) continue;
            glm::vec3 a = mesh.positions[mesh.indices[3 * t]];
            glm::vec3 b = mesh.positions[mesh.indices[3 * t + 1]];
            glm::vec3 c = mesh.positions[mesh.indices[3 * t + 2]];
            glm::vec3 cr = glm::cross(b - a, c - a);
            float area = 0.5f * glm::length(cr);
            if (!(area > 0.0f) || !std::isfinite(area)) continue;
            triangles_.push_back({a, b - a, c - a, glm::normalize(cr), m.emission, area});
            power.push_back(double(area) * double(std::max(luminance(m.emission), 1e-6f)));
            globalIndex.push_back(global);
        }
    }
    selectionPdf_.assign(global, 0.0f);
    double total = 0.0;
    for (double p : power) total += p;
    double running = 0.0;
    for (std::size_t i = 0; i < triangles_.size(); ++i) {
        running += power[i];
        cdf_.push_back(float(running / total));
        selectionPdf_[globalIndex[i]] = float(power[i] / total / double(triangles_[i].area));
    }
    if (!cdf_.empty()) cdf_.back() = 1.0f;
}

LightSample LightSampler::sampleDelta(std::size_t index, glm::vec3 p) const {
    // Deltas are never quads: the quad sample point is unused.
    const shading::IncidentLight incident = shading::evaluateLight(deltas_[index], p, glm::vec2(0.0f));
    LightSample s;
    s.direction = incident.direction;
    s.distance = incident.distance;
    s.radiance = incident.irradiance;
    return s;
}

LightSample LightSampler::sampleEmissive(glm::vec3 p, float u0, float u1, float u2) const {
    LightSample s;
    std::size_t i = std::size_t(std::lower_bound(cdf_.begin(), cdf_.end(), u0) - cdf_.begin());
    i = std::min(i, triangles_.size() - 1);
    const Emitter& e = triangles_[i];
    float su = std::sqrt(u1);
    glm::vec3 q = e.a + (1.0f - u2) * su * e.e1 + u2 * su * e.e2;
    glm::vec3 d = q - p;
    float d2 = glm::dot(d, d);
    if (!(d2 > 0.0f)) return s;
    s.distance = std::sqrt(d2);
    s.direction = d / s.distance;
    s.position = q;
    s.normal = e.normal;
    float cosLight = -glm::dot(e.normal, s.direction);
    if (cosLight <= 0.0f) return s;  // emitters shine from their front face only
    float pdfArea = (i == 0 ? cdf_[0] : cdf_[i] - cdf_[i - 1]) / e.area;
    s.pdf = pdfArea * d2 / cosLight;
    s.radiance = e.emission / s.pdf;
    return s;
}

float LightSampler::emissivePdf(std::uint32_t mesh, std::uint32_t triangle, float d2, float cosLight) const {
    float pdfArea = selectionPdf_[meshFirstTriangle_[mesh] + triangle];
    return pdfArea > 0.0f && cosLight > 0.0f ? pdfArea * d2 / cosLight : 0.0f;
}

}  // namespace voxgi::pt
