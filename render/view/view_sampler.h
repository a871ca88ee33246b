// Camera views of a scene drawn at random inside its free space, for judging a method over many
// views instead of the one someone chose (`voxgi eval --views N`). Eyes are drawn in voxels of
// the scene's occupancy that are empty with all 26 neighbours and that the scene's own camera
// reaches through empty voxels (no sealed cavities), and kept when rays from them see
// the scene around (not the sky through most directions) and few back faces (not inside a
// closed solid); each looks at the farthest of the front faces that random rays from it hit. The same scene, count
// and seed give the same views. Views are written and read as a viewer script's camera keys
// (render/view/view_script.h), so `voxgi view --script views.json` flies through them.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "scenes/scene.h"

namespace voxgi::view {

struct ViewSampling {
    int count = 0;
    std::uint64_t seed = 1;
    int voxelsAcross = 64;        // occupancy voxels along the scene's longest side
    float minSeenFraction = 0.5f; // of the probe rays from an eye that must hit geometry
    float maxBackFaceFraction = 0.1f;  // of those hits that may be back faces
    float minTargetDistance = 0.15f;   // from eye to target, in units of the scene's longest side
};

// `scene.camera` with the eye and target of each view (its up, lens, size and clip planes
// kept; the far plane grown to the scene's diagonal when shorter). Throws InputError when fewer
// than `count` views are found after 400 candidate eyes per view.
std::vector<Camera> sampleViews(const Scene& scene, const ViewSampling& sampling);

// The views of a viewer script's camera keys (each key one view, in frame order) on the scene's
// camera; InputError as ViewScript::load.
std::vector<Camera> readViews(const std::string& path, const Scene& scene);
// Writes views as such a script (keys at frames 0, 1, ...).
void writeViews(const std::string& path, const std::vector<Camera>& views);

}  // namespace voxgi::view
