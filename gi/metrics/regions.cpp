#include "gi/metrics/regions.h"

#include <cmath>
#include <limits>

#include "gi/metrics/flip.h"
#include "gi/metrics/image_metrics.h"
#include "scenes/camera_rays.h"
#include "scenes/errors.h"

namespace voxgi {

namespace {

const ImageLayer& requireLayer(const Image& image, const std::string& name, int channels, const char* which) {
    const ImageLayer* l = image.find(name);
    if (!l || l->channels != channels)
        throw InputError(std::string(which) + " image: no " + std::to_string(channels) + "-channel layer '" + name + "'");
    return *l;
}

bool inside(const Bounds& b, glm::vec3 p) {
    return glm::all(glm::greaterThanEqual(p, b.min)) && glm::all(glm::lessThanEqual(p, b.max));
}

}  // namespace

std::vector<int> regionOfPixels(const Image& reference, const Scene& scene) {
    const ImageLayer& depth = requireLayer(reference, "depth", 1, "reference");
    const ImageLayer& normal = requireLayer(reference, "normal", 3, "reference");
    const int w = reference.width(), h = reference.height();
    const CameraRays rays(scene.camera, w, h);
    // Within 45 degrees of the region's facing direction.
    const float cosLimit = std::sqrt(0.5f);
    std::vector<int> region(std::size_t(w) * std::size_t(h), -1);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const std::size_t i = std::size_t(y) * std::size_t(w) + std::size_t(x);
            if (!(depth.data[i] > 0.0f)) continue;  // no surface
            const glm::vec3 d = glm::normalize(rays.direction((float(x) + 0.5f) / float(w), (float(y) + 0.5f) / float(h)));
            const glm::vec3 p = rays.eye + depth.data[i] * d;
            const glm::vec3 n(normal.data[3 * i], normal.data[3 * i + 1], normal.data[3 * i + 2]);
            const float len = glm::length(n);
            for (std::size_t r = 0; r < scene.regions.size(); ++r) {
                const Region& reg = scene.regions[r];
                if (!inside(reg.box, p)) continue;
                if (reg.facing != glm::vec3(0.0f) && !(len > 0.0f && glm::dot(n, reg.facing) >= cosLimit * len)) continue;
                region[i] = int(r);
                break;
            }
        }
    return region;
}

std::vector<RegionMean> regionMeans(const Image& test, const Image& reference, const Scene& scene,
                                    const std::string& layer) {
    if (test.width() != reference.width() || test.height() != reference.height())
        throw InputError("region means: the images differ in size");
    const ImageLayer& t = requireLayer(test, layer, 3, "test");
    const ImageLayer& r = requireLayer(reference, layer, 3, "reference");
    const std::vector<int> region = regionOfPixels(reference, scene);
    const std::vector<double> relTerms = relativeSquaredErrorPerPixel(t.data, r.data, 3);
    const flip::HdrResult flipMap = flip::hdrFlip(t.data, r.data, test.width(), test.height());
    std::vector<RegionMean> out(scene.regions.size());
    for (std::size_t k = 0; k < out.size(); ++k) out[k].name = scene.regions[k].name;
    for (std::size_t i = 0; i < region.size(); ++i) {
        if (region[i] < 0) continue;
        RegionMean& m = out[std::size_t(region[i])];
        ++m.pixels;
        m.relMse += relTerms[i] / 3.0;
        m.flip += double(flipMap.error[i]);
        for (int c = 0; c < 3; ++c) {
            m.test[c] += double(t.data[3 * i + std::size_t(c)]);
            m.reference[c] += double(r.data[3 * i + std::size_t(c)]);
        }
    }
    for (RegionMean& m : out) {
        if (m.pixels == 0) {
            m.ratio = std::numeric_limits<double>::quiet_NaN();
            continue;
        }
        m.test /= double(m.pixels);
        m.reference /= double(m.pixels);
        m.relMse /= double(m.pixels);
        m.flip /= double(m.pixels);
        const double ref = m.reference.x + m.reference.y + m.reference.z;
        m.ratio = ref > 0.0 ? (m.test.x + m.test.y + m.test.z) / ref : std::numeric_limits<double>::quiet_NaN();
    }
    return out;
}

}  // namespace voxgi
