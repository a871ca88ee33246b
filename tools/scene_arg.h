// Scene arguments shared by the verbs: a scene JSON, a mesh file, or a built-in scene name
// ("cornell-box"), plus the camera-size and --set overrides every renderer accepts.
#pragma once

#include <initializer_list>
#include <optional>
#include <string>

#include "scenes/scene.h"
#include "tools/args.h"

namespace voxgi::cli {

// Loads SCENE (path or built-in name); InputError names the file and field on failure.
Scene loadSceneArgument(const std::string& argument);
// A scene a benchmark runs over: none (and a "NAME: skipped (why)" line on stdout) when it is a
// built-in scene other than the Cornell box whose meshes are absent beside the checkout; any
// other failure throws, as loadSceneArgument does.
std::optional<Scene> loadBenchScene(const std::string& name);
// Applies --width/--height, --backend cpu|gl (the backend setting of every method that has one)
// and --set section.key=value to a loaded scene.
void applySceneOverrides(const Args& args, Scene& scene);
// --method, else the scene's gi.method, else `fallback` (empty: InputError asking for one). An
// unknown name is an error naming where it came from (--method, or the scene file's gi.method).
std::string methodArgument(const Args& args, const Scene& scene, const std::string& fallback);
// Refuses, before any work starts, an output path whose directory does not exist or is not
// writable, or that names a directory, FIFO or device (a symlink names its target).
void requireWritable(const std::string& path, const std::string& option);
// requireWritable for each of `options` given, and none of them may name the same file as an
// input (a positional argument, or the value of one of `inputOptions`) or as another of them.
void requireOutputs(const Args& args, std::initializer_list<const char*> options,
                    std::initializer_list<const char*> inputOptions = {});

}  // namespace voxgi::cli
