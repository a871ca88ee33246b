// Quality presets for `voxgi eval`: per method, the gi settings behind "low", "medium" and
// "high" (one table, eval_presets.cpp). Baselines (direct, ambient) have one preset, "default".
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace voxgi::cli {

struct EvalPreset {
    std::string method;
    std::string name;
    std::vector<std::pair<std::string, std::string>> settings;  // gi keys, e.g. {"lpv.steps", "16"}
};

// The presets of `method` among `wanted` (baselines always give their one preset). InputError
// for an unknown preset name.
std::vector<EvalPreset> presetsFor(const std::string& method, const std::vector<std::string>& wanted);

}  // namespace voxgi::cli
