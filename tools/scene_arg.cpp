#include "tools/scene_arg.h"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <set>
#include <vector>

#include "gi/methods.h"
#include "gi/sky/sky_volume.h"
#include "scenes/atomic_file.h"
#include "scenes/errors.h"
#include "scenes/scene_loader.h"

namespace voxgi::cli {

namespace fs = std::filesystem;

namespace {
Scene loadSceneOrBuiltin(const std::string& argument) {
    if (!fs::exists(argument) && argument.find('/') == std::string::npos && fs::path(argument).extension().empty()) {
        std::string builtin = builtinScenePath(argument);
        if (fs::exists(builtin)) return loadSceneFile(builtin);
    }
    if (!fs::exists(argument)) throw InputError(argument + ": file not found");
    if (fs::is_directory(argument)) throw InputError(argument + ": is a directory, expected a scene or mesh file");
    return loadSceneOrMesh(argument);
}
}  // namespace

Scene loadSceneArgument(const std::string& argument) {
    Scene scene = loadSceneOrBuiltin(argument);
    requireRenderable(scene, argument);
    return scene;
}

std::optional<Scene> loadBenchScene(const std::string& name) {
    try {
        return loadSceneArgument(name);
    } catch (const InputError& e) {
        // Only a built-in scene whose meshes live beside the checkout may be missing.
        if (name == "cornell-box" || !std::filesystem::exists(builtinScenePath(name))) throw;
        std::printf("%s: skipped (%s)\n", name.c_str(), e.what());
        return std::nullopt;
    }
}

namespace {
// --set names a setting some method declares (gi/settings_table.h): a typo is an error, not a
// setting nothing reads.
void requireDeclaredSetting(const std::string& assignment) {
    const std::string key = assignment.substr(0, assignment.find('='));
    const std::string value = assignment.substr(assignment.find('=') + 1);
    std::set<std::string> sections, keys;
    // Methods that share a section may range a key differently (lpv.cascades: 1 for lpv, 1..5
    // for clpv): the value must suit at least one of them; the method that runs checks it again.
    std::string refused;
    bool accepted = false;
    // Every method's settings, and the frame's own components' (the sky-lighting volume).
    struct Owner {
        std::string name, section;
        std::vector<SettingInfo> settings;
    };
    std::vector<Owner> owners;
    for (const MethodInfo& m : methods())
        if (!m.section.empty()) owners.push_back({m.name, m.section, m.settings});
    owners.push_back({"sky volume", "sky", skyVolumeSettings().info()});
    for (const Owner& o : owners) {
        const std::string& owner = o.name;
        sections.insert(o.section);
        for (const SettingInfo& info : o.settings) {
            keys.insert(info.key);
            if (info.key != key) continue;
            try {
                validateSetting(info, value);
                accepted = true;
            } catch (const InputError& e) {
                // Every method's refusal, so the range of the method meant is among them.
                refused += (refused.empty() ? "" : "; ") + owner + ": " + e.what();
            }
        }
    }
    if (!accepted && !refused.empty()) throw InputError("--set " + assignment + ": " + refused);
    if (keys.count(key)) return;
    const std::string section = key.substr(0, key.find('.'));
    std::string known;
    if (sections.count(section)) {
        for (const std::string& k : keys)
            if (k.compare(0, section.size() + 1, section + ".") == 0) known += (known.empty() ? "" : ", ") + k;
    } else {
        for (const std::string& k : sections) known += (known.empty() ? "" : ", ") + k;
        known = "sections: " + known;
    }
    throw InputError("--set " + assignment + ": unknown setting (" + known + ")");
}
}  // namespace

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
    for (const std::string& s : args.values("--set")) {
        requireDeclaredSetting(s);
        scene.gi.applyOverride(s);
    }
}

std::string methodArgument(const Args& args, const Scene& scene, const std::string& fallback) {
    const bool given = args.has("--method");
    const std::string name = args.value("--method", scene.gi.getString("method", fallback));
    if (name.empty()) throw InputError("--method NAME is required (the scene names no gi.method)");
    try {
        findMethod(name);
    } catch (const InputError& e) {
        const std::string source = scene.sourcePath.empty() ? "scene" : scene.sourcePath;
        throw InputError((given ? std::string("--method ") : source + ": gi.method: ") + e.what());
    }
    return name;
}

void requireWritable(const std::string& path, const std::string& option) {
    std::string target;
    try {
        target = outputTarget(path);
    } catch (const InputError& e) {
        throw InputError(option + " " + e.what());
    }
    fs::path parent = fs::path(target).parent_path();
    if (parent.empty()) parent = ".";
    if (!fs::is_directory(parent))
        throw InputError(option + " " + path + ": directory " + parent.string() + " does not exist");
    if (::access(parent.c_str(), W_OK) != 0)
        throw InputError(option + " " + path + ": directory " + parent.string() + " is not writable");
}

namespace {
bool sameFile(const std::string& a, const std::string& b) {
    std::error_code ec;
    if (fs::exists(a, ec) && fs::exists(b, ec)) return fs::equivalent(a, b, ec);
    return fs::weakly_canonical(a, ec) == fs::weakly_canonical(b, ec);
}
}  // namespace

void requireOutputs(const Args& args, std::initializer_list<const char*> options,
                    std::initializer_list<const char*> inputOptions) {
    std::vector<std::string> inputs = args.positional();
    for (const char* option : inputOptions)
        if (auto path = args.value(option)) inputs.push_back(*path);
    std::vector<std::pair<std::string, std::string>> outputs;  // option, path
    for (const char* option : options)
        if (auto path = args.value(option)) {
            requireWritable(*path, option);
            outputs.emplace_back(option, *path);
        }
    for (std::size_t i = 0; i < outputs.size(); ++i) {
        const auto& [option, path] = outputs[i];
        for (const std::string& input : inputs)
            if (fs::exists(input) && sameFile(outputTarget(path), input))
                throw InputError(option + " " + path + ": is an input of this command (" + input + "); it would be overwritten");
        for (std::size_t j = 0; j < i; ++j)
            if (sameFile(outputTarget(path), outputTarget(outputs[j].second)))
                throw InputError(option + " " + path + ": the same file as " + outputs[j].first);
    }
}

}  // namespace voxgi::cli
