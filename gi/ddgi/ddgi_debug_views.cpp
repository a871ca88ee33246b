#include "gi/ddgi/ddgi_debug_views.h"

#include <algorithm>

#include "scenes/image.h"
#include "shaders/shared/constants.h"

namespace voxgi {

const SettingsTable<ProbesOptions>& probesOptions() {
    static const SettingsTable<ProbesOptions> table = [] {
        SettingsTable<ProbesOptions> t(kProbesView);
        t.choice("color", &ProbesOptions::color, {{"irradiance", ProbeColor::Irradiance}, {"state", ProbeColor::State}},
                 "irradiance: mean irradiance / pi, tone-mapped; state: green active, blue sleeping, red off");
        return t;
    }();
    return table;
}

std::vector<DebugViewInfo> ddgiDebugViews() {
    return {cascadeBoundsView("the box through each probe volume's probe grid"),
            {kProbesView, "DDGI probes", 'O', "every probe at its (relocated) position, radius 12 % of its volume's spacing",
             probesOptions().info(), 1}};
}

DebugDrawing probeBounds(const ProbeField& field) {
    DebugDrawing d;
    const auto& volumes = field.volumes();
    for (std::size_t i = 0; i < volumes.size(); ++i) {
        const ProbeVolume& v = volumes[i];
        glm::vec3 lo = v.basePosition(glm::ivec3(0)), hi = v.basePosition(v.counts - glm::ivec3(1));
        d.boxes.push_back({glm::min(lo, hi), glm::max(lo, hi), cascadeColor(int(i), int(volumes.size()))});
    }
    return d;
}

DebugDrawing probeSpheres(const ProbeField& field, ProbeColor color, float exposureStops) {
    DebugDrawing d;
    d.spheres.reserve(std::size_t(field.probeCount()));
    for (int p = 0; p < field.probeCount(); ++p) {
        const ProbeVolume& volume = field.volumes()[std::size_t(field.volumeOf(p))];
        float radius = 0.12f * std::min({volume.spacing.x, volume.spacing.y, volume.spacing.z});
        glm::vec3 c;
        if (color == ProbeColor::Irradiance) {
            c = toneMapToSrgb(field.meanIrradiance(p) * shading::kInvPi, exposureStops);
        } else {
            static const glm::vec3 states[3] = {{0.2f, 0.9f, 0.2f}, {0.2f, 0.4f, 1.0f}, {0.9f, 0.15f, 0.1f}};
            c = states[std::clamp(int(field.probes[std::size_t(p)].state), 0, 2)];
        }
        d.spheres.push_back({glm::vec4(field.probePosition(p), radius), glm::vec4(c.r, 0, 0, 0), glm::vec4(c.g, 0, 0, 0),
                             glm::vec4(c.b, 0, 0, 0)});
    }
    return d;
}

}  // namespace voxgi
