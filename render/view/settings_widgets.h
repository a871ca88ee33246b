// ImGui widgets made from setting declarations (gi/settings_table.h): a slider, checkbox, combo or
// text field per SettingInfo, editing the setting's text in a GiSettings (the scene's `gi` block,
// or a debug view's options). The widget keeps to the declared range, so what it writes parses.
#pragma once

#include "gi/settings_table.h"

namespace voxgi::view {

// Draws the widget; true when a new value is committed to `values` (a slider when released).
bool settingWidget(const SettingInfo& info, GiSettings& values);

}  // namespace voxgi::view
