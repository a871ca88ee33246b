#include <algorithm>
#include <cmath>

#include "gi/ddgi/ddgi_technique.h"
#include "render/view/sphere_set.h"
#include "scenes/image.h"
#include "shaders/shared/constants.h"

namespace voxgi::view {

SphereSet ddgiProbeSpheres(GiTechnique* technique, ProbeColor color, float exposureStops) {
    SphereSet set;
    auto* ddgi = dynamic_cast<DdgiTechnique*>(technique);
    if (!ddgi) return set;
    const ProbeField& field = ddgi->system().field();
    set.spheres.reserve(std::size_t(field.probeCount()));
    for (int p = 0; p < field.probeCount(); ++p) {
        const ProbeVolume& volume = field.volumes()[std::size_t(field.volumeOf(p))];
        float radius = 0.12f * std::min({volume.spacing.x, volume.spacing.y, volume.spacing.z});
        glm::vec3 c;
        if (color == ProbeColor::Irradiance) {
            // Radiance of a white diffuse surface lit by the probe's irradiance, as the frame shows it.
            c = toneMapToSrgb(field.meanIrradiance(p) / shading::kPi, exposureStops);
        } else {
            static const glm::vec3 states[3] = {{0.2f, 0.9f, 0.2f}, {0.2f, 0.4f, 1.0f}, {0.9f, 0.15f, 0.1f}};
            c = states[std::clamp(int(field.probes[std::size_t(p)].state), 0, 2)];
        }
        set.spheres.push_back({glm::vec4(field.probePosition(p), radius), glm::vec4(c.r, 0, 0, 0),
                               glm::vec4(c.g, 0, 0, 0), glm::vec4(c.b, 0, 0, 0)});
    }
    return set;
}

}  // namespace voxgi::view
