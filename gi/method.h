// A GI method as the tools know it before anything runs: its settings table, how to make its
// technique, the passes it plans for a scene, its eval presets, its debug views, the stiff cases it
// adds to the stability suite and its benchmark. Each method folder fills one MethodInfo;
// gi/methods.cpp lists them, one line each. The CLI, the viewer, eval and bench read only this.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "gi/debug_view.h"
#include "gi/settings_table.h"
#include "gi/technique.h"
#include "gi/technique_plan.h"
#include "scenes/image.h"
#include "scenes/scene.h"

namespace voxgi {

using SettingList = std::vector<std::pair<std::string, std::string>>;  // gi keys and values
// "key=value key=value", as reports and listings print a list.
std::string settingsText(const SettingList& settings);

// A named set of settings: eval's quality presets (low, medium, high), bench variants.
struct Preset {
    std::string name;
    SettingList settings;
};

// A stiff or extreme case a method adds to `voxgi eval --stability` (reported as NAME-METHOD):
// the scene rendered with `settings` must stay finite and, when `against` is given, its mean
// must match a render with `against` instead within `tolerance` (relative).
struct StressCase {
    enum class SceneKind { CornellBox, ClosedBox };  // ClosedBox: a 2 m box lit by a point light
    std::string name;
    std::string description;
    SceneKind scene = SceneKind::CornellBox;
    float albedo = 0.9f;  // ClosedBox walls
    int size = 24;        // image width and height
    int frames = 1;
    std::function<SettingList(const Scene&)> settings;
    std::function<SettingList(const Scene&)> against;  // may be empty
    double tolerance = 0.0;
};

// What `voxgi bench METHOD` hands a method's own benchmark: scenes loaded with the user's
// --set applied, and the frame counts asked for (0: the benchmark's defaults). Thread limits are
// set by the caller; a GL context is current when `gl` is true.
struct BenchRequest {
    std::vector<std::pair<std::string, Scene>> scenes;
    int frames = 0;
    int warmup = 0;
    int threads = 0;
    bool gl = false;
    std::string device;  // the GL device, when gl
};

// Renders the method with `extra` settings over the preset's; returns the frames' mean image.
using RenderWith = std::function<Image(const SettingList& extra)>;

struct MethodInfo {
    std::string name;     // --method NAME
    std::string summary;  // one line for listings
    bool built = true;    // false: named by the design, not implemented yet (exit 3)
    // Its settings: `gi.<section>.KEY`, declared once (gi/settings_table.h). Methods may share a
    // section (lpv and clpv).
    std::string section;
    std::vector<SettingInfo> settings;
    // Reads the settings as the technique will (every range and cross-setting rule): InputError
    // names the key. Needs no GL.
    std::function<void(const GiSettings&)> validate;
    // Bytes the technique will allocate with these (valid) settings, held to the memory limit
    // before anything is created (scenes/memory_limit.h); empty when small whatever the settings.
    std::function<double(const GiSettings&)> memoryBytes;
    // Makes the technique (a current GL context needed); null for direct light only.
    std::function<std::unique_ptr<GiTechnique>(const Scene&)> create;
    // The technique's passes for a scene and its settings (timer stage names), without GL.
    std::function<TechniquePlan(const Scene&)> plan;
    std::vector<Preset> presets;  // eval: low, medium, high; none = one run with the defaults
    // Oracle baselines only: the settings that fit the method's output to the reference (eval
    // renders with them and labels the row as an oracle).
    std::function<SettingList(const RenderWith&, const Image& reference)> fitToReference;
    std::vector<DebugViewInfo> debugViews;
    std::vector<StressCase> stressCases;
    std::vector<Preset> benchVariants;  // `voxgi bench frame`: settings compared side by side
    std::function<void(const BenchRequest&)> bench;  // its own `voxgi bench NAME`, may be empty

    bool oracle() const { return bool(fitToReference); }
    const SettingInfo* setting(const std::string& key) const;
};

// Fills a method's section, settings and validate from its table (tables are static: the
// reference stays valid).
template <typename Desc>
void declareSettings(MethodInfo& m, const SettingsTable<Desc>& table, const Desc& defaults = Desc{}) {
    m.section = table.section();
    m.settings = table.info(defaults);
    m.validate = [&table, defaults](const GiSettings& gi) { table.read(gi, defaults); };
}

}  // namespace voxgi
