// Debug views drawn over (or instead of) the frame with the viewer's camera: the voxelized
// geometry as cubes coloured by albedo or blocker strength, the scene bounds, light markers, and
// what the technique draws of its own state (gi/debug_view.h: boxes and spheres).
#pragma once

#include <memory>

#include <glm/glm.hpp>

#include "gi/debug_view.h"
#include "gl/program.h"
#include "gl/resources.h"
#include "scenes/scene.h"

namespace voxgi::view {

enum class VoxelColor { Albedo = 0, Blocker };

struct DebugViews {
    bool voxels = false;       // occupancy cubes of the voxelized scene (replaces the picture)
    VoxelColor voxelColor = VoxelColor::Albedo;
    int voxelResolution = 64;  // voxels along the scene's longest extent
    bool bounds = false;       // scene bounding box
    bool lights = true;        // markers at light positions / sun direction
    bool occludeSpheres = true; // spheres hidden behind the scene's surfaces (G-buffer test)
};

// Letterbox rectangle (x, y, w, h) of a render of renderW x renderH inside the window.
glm::ivec4 letterbox(int renderW, int renderH, int windowW, int windowH);

class DebugOverlay {
public:
    DebugOverlay();  // compiles shaders/view/*; call again to reload
    ~DebugOverlay();
    // Draws into the bound default framebuffer inside `viewport`; voxelizes on first use or
    // when the resolution changed. Returns the voxel count drawn (0 when voxels are off).
    // The technique's `drawings`: spheres depth-tested against each other and the voxel cubes,
    // and (occludeSpheres, not over voxels) against the frame's surfaces; boxes as lines.
    // `scenePosition`: the frame's G-buffer position texture (0: no occlusion by the scene).
    std::size_t draw(const Scene& scene, const DebugViews& views, glm::ivec4 viewport,
                     const std::vector<DebugDrawing>& drawings = {}, GLuint scenePosition = 0);

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace voxgi::view
