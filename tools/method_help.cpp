#include "tools/method_help.h"

#include "gi/methods.h"

namespace voxgi::cli {

std::string methodList() {
    std::string out = "methods (--method NAME):\n";
    for (const MethodInfo& m : methods())
        out += "  " + m.name + std::string(m.name.size() < 8 ? 8 - m.name.size() : 1, ' ') + m.summary +
               (m.built ? "" : " (not implemented yet)") + "\n";
    out += "`voxgi methods NAME` lists a method's settings (--set KEY=VALUE), presets and debug views.\n";
    return out;
}

std::string methodListWithSettings() {
    std::string out = methodList() + "main settings:\n";
    for (const MethodInfo& m : methods()) {
        std::string line;
        for (const SettingInfo& s : m.settings)
            if (s.main) line += (line.empty() ? "" : ", ") + s.key + "=" + s.defaultText + " (" + s.rangeText() + ")";
        if (!line.empty()) out += "  " + m.name + ": " + line + "\n";
    }
    return out;
}

}  // namespace voxgi::cli
