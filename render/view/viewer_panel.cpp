// The ImGui panel: frame time and per-stage GPU timings, method, its main settings, display
// mode, exposure, debug views, lights, and buttons for the key actions.
#include <algorithm>
#include <string>

#include <imgui.h>

#include "gi/methods.h"
#include "render/view/settings_widgets.h"
#include "render/view/viewer_state.h"

namespace voxgi::view {

namespace {

void timings(ViewerState& s) {
    ImGui::Text("frame %.1f ms (%.0f fps), %d accumulated", s.frameMs, s.frameMs > 0 ? 1000.0 / s.frameMs : 0.0,
                s.renderer->framesAccumulated());
    const auto& samples = s.renderer->timers().samples();
    ImGui::TextUnformatted("stages run this frame:");
    for (const std::string& stage : s.renderer->timers().stageOrder()) {
        auto it = samples.find(stage);
        if (it == samples.end()) continue;
        // Timers keep every sample: a stage ran this frame when it gained one since the last panel.
        std::size_t count = std::max(it->second.gpuMs.size(), it->second.cpuMs.size());
        std::size_t& seen = s.timerCounts[stage];
        bool ran = count != seen;
        seen = count;
        if (!ran) continue;
        double gpu = it->second.gpuMs.empty() ? 0.0 : it->second.gpuMs.back();
        double cpu = it->second.cpuMs.empty() ? 0.0 : it->second.cpuMs.back();
        ImGui::Text("  %-22s gpu %7.2f ms  cpu %7.2f ms", stage.c_str(), gpu, cpu);
    }
    if (const GiTechnique* t = s.renderer->technique()) {
        const std::vector<TechniqueStat> stats = t->stats();
        if (!stats.empty() && ImGui::TreeNode("technique stats (last update)")) {
            for (const TechniqueStat& st : stats)
                ImGui::Text("  %-24s %10.4g %s", st.name.c_str(), st.value, st.unit.c_str());
            ImGui::TreePop();
        }
    }
}

// The method, then its settings from its table: the main ones, the rest folded. A change
// writes scene.gi, which the rebuilt technique reads.
void methodSettings(ViewerState& s) {
    const std::vector<std::string> names = builtMethods();
    if (ImGui::BeginCombo("method (M)", s.method.c_str())) {
        for (const std::string& m : names)
            if (ImGui::Selectable(m.c_str(), m == s.method) && m != s.method) {
                s.method = m;
                s.rebuildTechnique = true;
            }
        ImGui::EndCombo();
    }
    const MethodInfo& method = findMethod(s.method);
    for (const SettingInfo& info : method.settings)
        if (info.main && settingWidget(info, s.scene.gi)) s.rebuildTechnique = true;
    if (method.settings.empty() || !ImGui::TreeNode("all settings")) return;
    for (const SettingInfo& info : method.settings)
        if (!info.main && settingWidget(info, s.scene.gi)) s.rebuildTechnique = true;
    ImGui::TreePop();
}

// The method's debug views: a checkbox each (with its key) and its options.
void methodViews(ViewerState& s) {
    for (const DebugViewInfo& info : findMethod(s.method).debugViews) {
        MethodView& view = s.methodViews[info.name];
        std::string label = info.label + (info.key ? std::string(" (") + info.key + ")" : "");
        if (ImGui::Checkbox(label.c_str(), &view.on)) view.drawnFrame = -1000;
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", info.doc.c_str());
        if (!view.on) continue;
        ImGui::Indent();
        for (const SettingInfo& option : info.options)
            if (settingWidget(option, view.options)) view.drawnFrame = -1000;
        ImGui::Unindent();
    }
}

void lightControls(ViewerState& s) {
    ImGui::Checkbox("animate lights (L)", &s.animateLights);
    if (s.scene.lights.empty()) return;
    Light& main = s.scene.lights[0];
    bool changed = false;
    if (main.type == LightType::Directional) {
        changed = ImGui::DragFloat3("main light direction", &main.direction.x, 0.01f);
        if (changed && glm::length(main.direction) > 1e-6f) main.direction = glm::normalize(main.direction);
    } else {
        changed = ImGui::DragFloat3("main light position", &main.position.x, 0.005f * s.sceneRadius);
    }
    if (changed) {
        s.animator.setRest(s.scene.lights);
        s.viewChanged = true;
    }
}

}  // namespace

void drawPanel(ViewerState& s) {
    ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowBgAlpha(0.75f);
    if (!ImGui::Begin("voxgi (F1 hides)")) {
        ImGui::End();
        return;
    }
    timings(s);
    ImGui::Separator();
    methodSettings(s);
    ImGui::Checkbox("auto exposure", &s.autoExposure);
    ImGui::SameLine();
    if (s.autoExposure) ImGui::Text("%.1f stops", double(s.exposure));
    else ImGui::SliderFloat("exposure (stops)", &s.exposure, -10.0f, 10.0f, "%.1f");
    const char* curves[2] = {"filmic", "reinhard"};
    ImGui::Combo("tone curve", &s.toneCurve, curves, 2);
    int mode = int(s.mode);
    const char* modes[kDisplayModeCount];
    for (int i = 0; i < kDisplayModeCount; ++i) modes[i] = displayModeName(DisplayMode(i));
    ImGui::Combo("show (1-5)", &mode, modes, kDisplayModeCount);
    s.mode = DisplayMode(mode);
    ImGui::SliderFloat("speed (+/-, wheel)", &s.speed, 0.01f * s.sceneRadius, 10.0f * s.sceneRadius, "%.3f",
                       ImGuiSliderFlags_Logarithmic);
    ImGui::Separator();
    ImGui::Checkbox("voxels (G)", &s.debug.voxels);
    ImGui::SameLine();
    int color = int(s.debug.voxelColor);
    ImGui::RadioButton("albedo", &color, 0);
    ImGui::SameLine();
    ImGui::RadioButton("blocker", &color, 1);
    s.debug.voxelColor = VoxelColor(color);
    ImGui::SliderInt("voxel resolution", &s.debug.voxelResolution, 8, 128);
    ImGui::Checkbox("spheres hidden by scene", &s.debug.occludeSpheres);
    methodViews(s);
    ImGui::Checkbox("scene bounds (B)", &s.debug.bounds);
    ImGui::SameLine();
    ImGui::Checkbox("light markers", &s.debug.lights);
    ImGui::Separator();
    lightControls(s);
    ImGui::Separator();
    if (ImGui::Button("screenshot (P)")) s.takeScreenshot = true;
    ImGui::SameLine();
    if (ImGui::Button("dump .vdb (V)")) s.dumpVdb = true;
    ImGui::SameLine();
    if (ImGui::Button("reload shaders (F5)")) s.reloadShaders = true;
    if (!s.status.empty()) ImGui::TextWrapped("%s", s.status.c_str());
    ImGui::End();
}

}  // namespace voxgi::view
