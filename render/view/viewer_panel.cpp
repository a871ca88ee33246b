// The ImGui panel: frame time and per-stage GPU timings, method, its main settings, display
// mode, exposure, debug views, lights, and buttons for the key actions.
#include <algorithm>
#include <string>

#include <imgui.h>

#include "gi/ddgi/ddgi_desc.h"
#include "gi/lpv/lpv_desc.h"
#include "render/frame/techniques.h"
#include "render/view/viewer_state.h"

namespace voxgi::view {

namespace {

// An integer gi setting edited in place: writes scene.gi and asks for a rebuild on change.
void intSetting(ViewerState& s, const char* label, const std::string& key, int fallback, int lo, int hi) {
    int v = s.scene.gi.getInt(key, fallback);
    if (ImGui::SliderInt(label, &v, lo, hi)) {
        s.scene.gi.set(key, std::to_string(v));
        s.rebuildTechnique = true;
    }
}

void floatSetting(ViewerState& s, const char* label, const std::string& key, float fallback, float lo, float hi) {
    float v = s.scene.gi.getFloat(key, fallback);
    // Rebuild once the slider is released: rebuilding a technique per pixel of drag is slow.
    ImGui::SliderFloat(label, &v, lo, hi, "%.3f");
    if (ImGui::IsItemEdited()) s.scene.gi.set(key, std::to_string(v));
    if (ImGui::IsItemDeactivatedAfterEdit()) s.rebuildTechnique = true;
}

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
}

void methodSettings(ViewerState& s) {
    const std::vector<std::string> methods = builtMethods();
    if (ImGui::BeginCombo("method (M)", s.method.c_str())) {
        for (const std::string& m : methods)
            if (ImGui::Selectable(m.c_str(), m == s.method) && m != s.method) {
                s.method = m;
                s.rebuildTechnique = true;
            }
        ImGui::EndCombo();
    }
    // The sliders start at the values the technique reads (its defaults or the scene's), and
    // write scene.gi, which the rebuilt technique reads back.
    if (s.method == "lpv" || s.method == "clpv") {
        LpvDesc d = LpvDesc::fromSettings(s.scene.gi, s.method == "clpv");
        intSetting(s, "propagation steps", "lpv.steps", d.steps, 1, 64);
        if (s.method == "clpv") intSetting(s, "cascades", "lpv.cascades", d.cascades, 1, 6);
        intSetting(s, "resolution", "lpv.resolution", d.resolution, 8, 128);
    } else if (s.method == "ddgi") {
        DdgiDesc d = readDdgiDesc(s.scene.gi);
        intSetting(s, "rays per probe", "ddgi.rays", d.rays, 16, 1024);
        floatSetting(s, "hysteresis", "ddgi.hysteresis", d.hysteresis, 0.0f, 0.999f);
        intSetting(s, "cascades", "ddgi.cascades", d.cascades, 1, 4);
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
    ImGui::SliderFloat("exposure (stops)", &s.exposure, -10.0f, 10.0f, "%.1f");
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
    if (ImGui::Checkbox("LPV cells (H)", &s.debug.lpvCells)) s.lpvSpheresFrame = -1000;
    ImGui::SameLine();
    ImGui::SetNextItemWidth(80);
    if (ImGui::SliderInt("cascade", &s.debug.lpvCascade, 0, 5)) s.lpvSpheresFrame = -1000;
    ImGui::SameLine();
    ImGui::SetNextItemWidth(80);
    if (ImGui::SliderInt("stride", &s.debug.lpvStride, 1, 8)) s.lpvSpheresFrame = -1000;
    ImGui::Checkbox("cascade bounds (C)", &s.debug.cascades);
    ImGui::SameLine();
    ImGui::Checkbox("spheres hidden by scene", &s.debug.occludeSpheres);
    ImGui::Checkbox("DDGI probes (O)", &s.debug.probes);
    ImGui::SameLine();
    int probeColor = int(s.debug.probeColor);
    ImGui::RadioButton("irradiance", &probeColor, 0);
    ImGui::SameLine();
    ImGui::RadioButton("state", &probeColor, 1);
    s.debug.probeColor = ProbeColor(probeColor);
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
