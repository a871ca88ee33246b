// Reflective shadow maps: the scene rasterized from each light, every texel a surfel with the
// diffuse flux it reflects (W). Directional lights use an orthographic map over the scene,
// spot lights a perspective one, point lights six 90-degree faces, quad lights the faces of a
// hemicube at their centre with intensity L A cos(theta).
#pragma once

#include <memory>
#include <vector>

#include "gi/lpv/surfels.h"
#include "scenes/scene.h"

namespace voxgi {

class SceneGpu;

class RsmRenderer {
public:
    explicit RsmRenderer(int size);
    ~RsmRenderer();
    RsmRenderer(const RsmRenderer&) = delete;
    RsmRenderer& operator=(const RsmRenderer&) = delete;

    // One source per rendered face. Needs a current GL context.
    std::vector<SurfelSource> render(const Scene& scene, const SceneGpu& gpu, const Light& light);

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace voxgi
