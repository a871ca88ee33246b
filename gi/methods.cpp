#include "gi/methods.h"

#include <set>

#include "scenes/errors.h"
#include "scenes/memory_limit.h"

namespace voxgi {

// Each method folder's description (gi/<method>/<method>_method.cpp).
MethodInfo directMethod(), ambientMethod(), lpvMethod(), clpvMethod(), ddgiMethod(), isrMethod(), hybridMethod();

namespace {

MethodInfo planned(const char* name, const char* summary) {
    MethodInfo m;
    m.name = name;
    m.summary = summary;
    m.built = false;
    return m;
}

}  // namespace

const std::vector<MethodInfo>& methods() {
    // The method list: one line per method.
    static const std::vector<MethodInfo> all = {
        directMethod(),
        ambientMethod(),
        lpvMethod(),
        clpvMethod(),
        planned("ilpv", "incremental LPV: 26-neighbour stochastic transfer, reuse of earlier frames (seed 001)"),
        ddgiMethod(),
        isrMethod(),
        hybridMethod(),
    };
    return all;
}

std::string settingsText(const SettingList& settings) {
    std::string out;
    for (const auto& [k, v] : settings) out += (out.empty() ? "" : " ") + k + "=" + v;
    return out;
}

const SettingInfo* MethodInfo::setting(const std::string& key) const {
    for (const SettingInfo& s : settings)
        if (s.key == key) return &s;
    return nullptr;
}

const MethodInfo& findMethod(const std::string& name) {
    std::string known;
    for (const MethodInfo& m : methods()) {
        if (m.name == name) {
            if (!m.built) throw NotImplementedError("method '" + name + "' is not implemented yet");
            return m;
        }
        known += (known.empty() ? "" : ", ") + m.name;
    }
    throw InputError(name + ": unknown method (known: " + known + ")");
}

std::vector<std::string> builtMethods() {
    std::vector<std::string> out;
    for (const MethodInfo& m : methods())
        if (m.built) out.push_back(m.name);
    return out;
}

std::vector<std::string> plannedMethods() {
    std::vector<std::string> out;
    for (const MethodInfo& m : methods())
        if (!m.built) out.push_back(m.name);
    return out;
}

const MethodInfo& validateMethod(const std::string& name, const Scene& scene) {
    const MethodInfo& m = findMethod(name);
    m.validate(scene.gi);
    if (m.memoryBytes) requireMemory(m.memoryBytes(scene.gi), "method " + name + " with its gi." + m.section + " settings");
    return m;
}

std::unique_ptr<GiTechnique> createTechnique(const std::string& name, const Scene& scene) {
    const MethodInfo& m = validateMethod(name, scene);
    return m.create ? m.create(scene) : nullptr;
}

void setForEveryMethod(GiSettings& gi, const std::string& key, const std::string& value) {
    std::set<std::string> sections;
    for (const MethodInfo& m : methods()) {
        const SettingInfo* s = m.built && !m.section.empty() ? m.setting(m.section + "." + key) : nullptr;
        if (!s || !sections.insert(m.section).second) continue;
        // Checked here so the error is about the value, not about a key the user did not type.
        try {
            validateSetting(*s, value);
        } catch (const InputError&) {
            throw InputError("expected " + s->rangeText() + ", got '" + value + "'");
        }
        gi.set(s->key, value);
    }
    if (sections.empty()) throw InputError("no method has a setting '" + key + "'");
}

}  // namespace voxgi
