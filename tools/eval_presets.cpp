#include "tools/eval_presets.h"

#include "scenes/errors.h"

namespace voxgi::cli {

namespace {

// lpv.reuse=false: the LPV skips its work when nothing changed, which would time an empty frame.
const EvalPreset kPresets[] = {
    {"direct", "default", {}},
    {"ambient", "default", {}},
    {"lpv", "low", {{"lpv.resolution", "16"}, {"lpv.steps", "8"}, {"lpv.reuse", "false"}}},
    {"lpv", "medium", {{"lpv.resolution", "32"}, {"lpv.steps", "16"}, {"lpv.reuse", "false"}}},
    {"lpv", "high", {{"lpv.resolution", "32"}, {"lpv.steps", "32"}, {"lpv.reuse", "false"}}},
    {"clpv", "low", {{"lpv.resolution", "16"}, {"lpv.steps", "8"}, {"lpv.cascades", "2"}, {"lpv.reuse", "false"}}},
    {"clpv", "medium", {{"lpv.resolution", "32"}, {"lpv.steps", "16"}, {"lpv.cascades", "3"}, {"lpv.reuse", "false"}}},
    {"clpv", "high", {{"lpv.resolution", "32"}, {"lpv.steps", "32"}, {"lpv.cascades", "4"}, {"lpv.reuse", "false"}}},
    {"ddgi", "low", {{"ddgi.rays", "64"}, {"ddgi.probes", "4,4,4"}}},
    {"ddgi", "medium", {{"ddgi.rays", "128"}, {"ddgi.probes", "8,8,8"}}},
    {"ddgi", "high", {{"ddgi.rays", "256"}, {"ddgi.probes", "10,10,10"}}},
};

bool isBaseline(const std::string& method) { return method == "direct" || method == "ambient"; }

}  // namespace

std::vector<EvalPreset> presetsFor(const std::string& method, const std::vector<std::string>& wanted) {
    for (const std::string& w : wanted)
        if (w != "low" && w != "medium" && w != "high")
            throw InputError("--presets " + w + ": unknown preset (known: low, medium, high)");
    std::vector<EvalPreset> out;
    for (const EvalPreset& p : kPresets) {
        if (p.method != method) continue;
        if (isBaseline(method)) {
            out.push_back(p);
            continue;
        }
        for (const std::string& w : wanted)
            if (p.name == w) out.push_back(p);
    }
    // A built method without a row runs with its own defaults.
    if (out.empty()) out.push_back({method, "default", {}});
    return out;
}

}  // namespace voxgi::cli
