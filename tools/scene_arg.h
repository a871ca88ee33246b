// Scene arguments shared by the verbs: a scene JSON, a mesh file, or a built-in scene name
// ("cornell-box"), plus the camera-size and --set overrides every renderer accepts.
#pragma once

#include <string>

#include "scenes/scene.h"
#include "tools/args.h"

namespace voxgi::cli {

// Loads SCENE (path or built-in name); InputError names the file and field on failure.
Scene loadSceneArgument(const std::string& argument);
// Applies --width/--height, --backend cpu|gl (the backend setting of every method that has one)
// and --set section.key=value to a loaded scene.
void applySceneOverrides(const Args& args, Scene& scene);
// Refuses an output path whose directory does not exist before any work starts.
void requireWritable(const std::string& path, const std::string& option);

}  // namespace voxgi::cli
