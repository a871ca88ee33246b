#include "gi/debug_view.h"

namespace voxgi {

DebugViewInfo cascadeBoundsView(std::string doc) {
    return {kCascadeBoundsView, "cascade bounds", 'C', std::move(doc) + ", finest orange to coarsest cyan", {}, 1};
}

glm::vec3 cascadeColor(int i, int count) {
    float t = count > 1 ? float(i) / float(count - 1) : 0.0f;
    return glm::mix(glm::vec3(1.0f, 0.55f, 0.1f), glm::vec3(0.2f, 0.8f, 1.0f), t);
}

}  // namespace voxgi
