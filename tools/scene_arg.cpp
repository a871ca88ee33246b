#include "tools/scene_arg.h"

#include <filesystem>

#include "gi/methods.h"
#include "scenes/errors.h"
#include "scenes/scene_loader.h"

namespace voxgi::cli {

namespace fs = std::filesystem;

Scene loadSceneArgument(const std::string& argument) {
    if (!fs::exists(argument) && argument.find('/') == std::string::npos && fs::path(argument).extension().empty()) {
        std::string builtin = builtinScenePath(argument);
        if (fs::exists(builtin)) return loadSceneFile(builtin);
    }
    if (!fs::exists(argument)) throw InputError(argument + ": file not found");
    if (fs::is_directory(argument)) throw InputError(argument + ": is a directory, expected a scene or mesh file");
    return loadSceneOrMesh(argument);
}

void applySceneOverrides(const Args& args, Scene& scene) {
    scene.camera.width = args.integer("--width", scene.camera.width, 1, 16384);
    scene.camera.height = args.integer("--height", scene.camera.height, 1, 16384);
    if (auto backend = args.value("--backend")) {
        try {
            setForEveryMethod(scene.gi, "backend", *backend);
        } catch (const InputError& e) {
            throw InputError("--backend " + *backend + ": " + e.what());
        }
    }
    for (const std::string& s : args.values("--set")) scene.gi.applyOverride(s);
}

void requireWritable(const std::string& path, const std::string& option) {
    fs::path parent = fs::path(path).parent_path();
    if (!parent.empty() && !fs::is_directory(parent))
        throw InputError(option + " " + path + ": directory " + parent.string() + " does not exist");
    if (fs::is_directory(path)) throw InputError(option + " " + path + ": is a directory");
}

}  // namespace voxgi::cli
