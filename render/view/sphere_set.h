// Spheres for the debug overlay: DDGI probes (constant colours) and light-volume cells (2-band
// SH per colour channel painted on the sphere).
#pragma once

#include <vector>

#include <glm/glm.hpp>

namespace voxgi {
class GiTechnique;
}

namespace voxgi::view {

struct SphereInstance {
    glm::vec4 centerRadius;
    glm::vec4 r, g, b;  // constant colour in .x, or SH coefficients
};

struct SphereSet {
    std::vector<SphereInstance> spheres;
    bool sh = false;      // false: constant colours
    float scale = 1.0f;   // SH: multiplier before tone mapping
};

enum class ProbeColor { Irradiance = 0, State };

// The DDGI probes of `technique` (empty unless it is ddgi): irradiance = the probe's mean
// irradiance / pi tone-mapped with `exposureStops`; state = green active, blue sleeping, red off.
SphereSet ddgiProbeSpheres(GiTechnique* technique, ProbeColor color, float exposureStops);

}  // namespace voxgi::view
