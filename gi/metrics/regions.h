// Mean light per scene region (Scene::regions) of a test image against the reference: where the
// energy of a method goes, region by region, without cancelling over the whole image.
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scenes/image.h"
#include "scenes/scene.h"

namespace voxgi {

struct RegionMean {
    std::string name;
    std::size_t pixels = 0;       // reference pixels whose surface point lies in the region
    glm::dvec3 test{0.0}, reference{0.0};  // mean of the layer over those pixels
    double ratio = 0.0;           // test / reference, on the sum of the three channels (NaN if 0)
    // The error over those pixels alone (a mask: mirrors, glass, a wall): relMSE's mean term and
    // the mean of the whole image's HDR-FLIP map (its exposures from the whole reference).
    double relMse = 0.0, flip = 0.0;
};

// Which region each pixel belongs to, from the reference's `depth` and `normal` layers (the path
// tracer's: distance along the primary ray and the surface normal) and the scene's camera:
// -1 for none, else the first region (in scene order) containing the pixel centre's point.
std::vector<int> regionOfPixels(const Image& reference, const Scene& scene);

// Per region of the scene, the mean of `layer` (3 channels) in both images and the error. Throws InputError
// when a layer is missing or the sizes differ.
std::vector<RegionMean> regionMeans(const Image& test, const Image& reference, const Scene& scene,
                                    const std::string& layer);

}  // namespace voxgi
