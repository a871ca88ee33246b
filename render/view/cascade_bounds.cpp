#include "gi/ddgi/ddgi_technique.h"
#include "gi/lpv/cascades.h"
#include "gi/lpv/lpv_technique.h"
#include "render/view/sphere_set.h"

namespace voxgi::view {

namespace {
// Finer cascades warmer: cascade 0 orange, then toward cyan.
glm::vec3 cascadeColor(int i, int count) {
    float t = count > 1 ? float(i) / float(count - 1) : 0.0f;
    return glm::mix(glm::vec3(1.0f, 0.55f, 0.1f), glm::vec3(0.2f, 0.8f, 1.0f), t);
}
}  // namespace

std::vector<DebugBox> cascadeBoxes(GiTechnique* technique, const Bounds& sceneBounds, const Camera& camera) {
    std::vector<DebugBox> boxes;
    if (auto* lpv = dynamic_cast<LpvTechnique*>(technique)) {
        // The same call with the same arguments as the technique's own placement.
        std::vector<CascadePlacement> cascades =
            placeCascades(lpv->desc(), sceneBounds, camera.eye, camera.target - camera.eye);
        for (std::size_t i = 0; i < cascades.size(); ++i)
            boxes.push_back({cascades[i].grid.worldMin(), cascades[i].grid.worldMax(),
                             cascadeColor(int(i), int(cascades.size()))});
    } else if (auto* ddgi = dynamic_cast<DdgiTechnique*>(technique)) {
        const auto& volumes = ddgi->system().field().volumes();
        for (std::size_t i = 0; i < volumes.size(); ++i) {
            const ProbeVolume& v = volumes[i];
            glm::vec3 lo = v.basePosition(glm::ivec3(0));
            glm::vec3 hi = v.basePosition(v.counts - glm::ivec3(1));
            boxes.push_back({glm::min(lo, hi), glm::max(lo, hi), cascadeColor(int(i), int(volumes.size()))});
        }
    }
    return boxes;
}

}  // namespace voxgi::view
