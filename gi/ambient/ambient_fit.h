// Fitting the ambient baseline's irradiance to a reference. The rendered indirect layer is
// linear in E (pixel i, channel c: k_ic * E_c with k = diffuse albedo / pi), so rendering once
// with E = 1 gives k, and E_c = sum_i r_ic / sum_i k_ic makes the mean of the rendered indirect
// layer equal the reference's mean indirect light exactly (pixels where either value is not
// finite are left out of both sums).
#pragma once

#include <glm/glm.hpp>

#include "scenes/image.h"

namespace voxgi {

// Both layers RGB and of equal size, else InputError. A channel with no response (sum k = 0)
// gets E = 0.
glm::vec3 fitAmbientIrradiance(const ImageLayer& unitResponse, const ImageLayer& referenceIndirect);

}  // namespace voxgi
