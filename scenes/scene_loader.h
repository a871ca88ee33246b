// Reading scenes: the JSON scene format (docs/scene-format.md) and bare mesh files.
#pragma once

#include <string>

#include "scenes/scene.h"

namespace voxgi {

// Loads a scene JSON file. Throws InputError with "<file>: <field or line>: <problem>".
Scene loadSceneFile(const std::string& path);

// Parses scene JSON text; `path` names the file in messages and anchors relative mesh paths.
Scene parseSceneJson(const std::string& text, const std::string& path);

// Builds a scene around one mesh file (OBJ, glTF, PLY...) with a default camera framing it and
// a sun, for tools that accept a bare mesh.
Scene sceneFromMeshFile(const std::string& path);

// Loads a scene file when the path ends in .json, otherwise wraps a mesh file.
Scene loadSceneOrMesh(const std::string& path);

// The largest coordinate voxgi accepts (m): products and squared distances of coordinates
// (up to 1e24) stay far from float's overflow (3.4e38), which a 3e38 m vertex reaches at once.
constexpr float kMaxCoordinate = 1e12f;
// Refuses (InputError naming the source and field) a scene nothing can be rendered from: no
// triangle with finite vertices and non-zero area, coordinates beyond kMaxCoordinate, or a
// camera that is not finite or looks nowhere.
void requireRenderable(const Scene& scene, const std::string& source);

// The directory holding built-in scenes (scenes/ in the source tree unless VOXGI_SCENE_DIR is
// set in the environment); `builtinScenePath("cornell-box")` -> ".../cornell-box.json".
std::string builtinScenePath(const std::string& name);

}  // namespace voxgi
