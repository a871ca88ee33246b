// Spheres for the debug overlay: DDGI probes (constant colours) and light-volume cells (2-band
// SH per colour channel painted on the sphere).
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scenes/scene.h"

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

// The light volume of cascade `cascade` of an lpv/clpv technique (empty otherwise), one sphere
// per `stride`-th cell along each axis holding light, painted with the cell's 2-band SH
// intensity. Read back through the technique's own .vdb dump (written to `scratchPath`), the
// one public view of its state. `scale` maps the brightest cell's mean intensity to 1, times
// 2^exposureStops.
// Boxes of the technique's cascades (lpv/clpv: the light volumes as placed for `camera`, from
// gi/lpv/cascades.h; ddgi: each probe volume's probe bounds); empty for other methods.
struct DebugBox {
    glm::vec3 min, max, color;
};
std::vector<DebugBox> cascadeBoxes(GiTechnique* technique, const Bounds& sceneBounds, const Camera& camera);

SphereSet lpvCellSpheres(GiTechnique* technique, int cascade, int stride, float exposureStops,
                         const std::string& scratchPath);

}  // namespace voxgi::view
