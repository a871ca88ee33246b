#include "render/view/settings_widgets.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <exception>

#include <imgui.h>

namespace voxgi::view {

namespace {

// The value as the technique reads it: the one set, else the default (also when the one set is
// refused, which the technique reports on its own).
template <typename T, typename Parse>
T current(const SettingInfo& info, const GiSettings& values, Parse parse) {
    if (values.has(info.key)) {
        try {
            return parse(info, values.getString(info.key, ""));
        } catch (const std::exception&) {
        }
    }
    return parse(info, info.defaultText);
}

void tooltip(const SettingInfo& info) {
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s\n%s (default %s)", info.doc.c_str(), info.rangeText().c_str(),
                                                  info.defaultText.c_str());
}

// Sliders write while dragged (so the next frame shows the value) and commit when released.
bool draggedValue(const SettingInfo& info, GiSettings& values, const std::string& text) {
    if (ImGui::IsItemEdited()) values.set(info.key, text);
    tooltip(info);
    return ImGui::IsItemDeactivatedAfterEdit();
}

}  // namespace

bool settingWidget(const SettingInfo& info, GiSettings& values) {
    const std::string name = info.key.substr(info.key.find('.') + 1);
    const std::string label = name + "##" + info.key;
    switch (info.kind) {
        case SettingKind::Integer: {
            int v = current<int>(info, values, parseInteger);
            if (!info.fitWord.empty()) {
                // Fitted by the technique, or a number (starting from the range's low end).
                bool fitted = v == kFittedInteger;
                const bool toggled = ImGui::Checkbox((info.fitWord + "##fit" + info.key).c_str(), &fitted);
                tooltip(info);
                if (toggled) {
                    values.set(info.key, fitted ? info.fitWord : std::to_string(int(info.min)));
                    return true;
                }
                if (fitted) return false;
                ImGui::SameLine();
            }
            if (info.min == info.max) {
                ImGui::TextDisabled("%s = %d", name.c_str(), v);
                tooltip(info);
                return false;
            }
            const long steps = long((info.max - info.min) / info.step);
            if (steps <= 4096) {
                int k = int((v - int(info.min)) / info.step);
                ImGui::SliderInt(label.c_str(), &k, 0, int(steps), std::to_string(v).c_str());
                v = int(info.min) + k * info.step;
            } else {
                ImGui::InputInt(label.c_str(), &v);
                v = int(std::clamp(double(v), info.min, info.max));
            }
            return draggedValue(info, values, std::to_string(v));
        }
        case SettingKind::Number: {
            float v = current<float>(info, values, parseNumber);
            const float lo = float(info.min), hi = float(info.max);
            if (hi - lo <= 1000.0f) {
                const bool logarithmic = lo > 0.0f && hi / lo > 100.0f;
                ImGui::SliderFloat(label.c_str(), &v, lo, hi, "%.3g", logarithmic ? ImGuiSliderFlags_Logarithmic : 0);
            } else {
                ImGui::InputFloat(label.c_str(), &v, 0.0f, 0.0f, "%.4g");
            }
            v = std::clamp(v, lo, hi);
            return draggedValue(info, values, formatNumber(v));
        }
        case SettingKind::Flag: {
            bool v = current<bool>(info, values, parseFlag);
            const bool changed = ImGui::Checkbox(label.c_str(), &v);
            tooltip(info);
            if (changed) values.set(info.key, v ? "true" : "false");
            return changed;
        }
        case SettingKind::Choice: {
            const std::size_t chosen = current<std::size_t>(info, values, parseChoice);
            bool changed = false;
            if (ImGui::BeginCombo(label.c_str(), info.choices[chosen].c_str())) {
                for (std::size_t i = 0; i < info.choices.size(); ++i)
                    if (ImGui::Selectable(info.choices[i].c_str(), i == chosen) && i != chosen) {
                        values.set(info.key, info.choices[i]);
                        changed = true;
                    }
                ImGui::EndCombo();
            }
            tooltip(info);
            return changed;
        }
        case SettingKind::Triple: {
            // Text ("x,y,z", one value or the fit word), committed with Enter when it parses.
            char text[128];
            std::snprintf(text, sizeof text, "%s", values.getString(info.key, info.defaultText).c_str());
            const bool entered = ImGui::InputText(label.c_str(), text, sizeof text, ImGuiInputTextFlags_EnterReturnsTrue);
            tooltip(info);
            if (!entered) return false;
            try {
                validateSetting(info, text);
            } catch (const std::exception&) {
                return false;
            }
            values.set(info.key, text);
            return true;
        }
    }
    return false;
}

}  // namespace voxgi::view
