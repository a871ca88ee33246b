#include "gi/ambient/ambient_fit.h"

#include <cmath>

#include "scenes/errors.h"

namespace voxgi {

glm::vec3 fitAmbientIrradiance(const ImageLayer& unitResponse, const ImageLayer& referenceIndirect) {
    if (unitResponse.channels != 3 || referenceIndirect.channels != 3)
        throw InputError("ambient fit: the indirect layers must be RGB");
    if (unitResponse.data.size() != referenceIndirect.data.size())
        throw InputError("ambient fit: the rendered and reference images differ in size");
    // Double sums: a 4K image has 8M terms per channel.
    double response[3] = {0, 0, 0}, reference[3] = {0, 0, 0};
    for (std::size_t i = 0; i < unitResponse.data.size(); ++i) {
        double k = unitResponse.data[i], r = referenceIndirect.data[i];
        if (!std::isfinite(k) || !std::isfinite(r)) continue;
        response[i % 3] += k;
        reference[i % 3] += r;
    }
    glm::vec3 e(0.0f);
    for (int c = 0; c < 3; ++c) e[c] = response[c] > 0.0 ? float(reference[c] / response[c]) : 0.0f;
    return e;
}

}  // namespace voxgi
