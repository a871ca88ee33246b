#include "scenes/gi_settings.h"

#include "scenes/errors.h"

namespace voxgi {

std::string GiSettings::getString(const std::string& key, const std::string& fallback) const {
    auto it = values_.find(key);
    return it == values_.end() ? fallback : it->second;
}

void GiSettings::applyOverride(const std::string& assignment) {
    auto eq = assignment.find('=');
    auto dot = assignment.find('.');
    if (eq == std::string::npos || dot == std::string::npos || dot > eq || dot == 0 ||
        dot + 1 == eq || eq + 1 == assignment.size())
        throw InputError("--set " + assignment + ": expected section.key=value");
    set(assignment.substr(0, eq), assignment.substr(eq + 1));
}

std::vector<std::string> GiSettings::unknownKeys(const std::string& section,
                                                 const std::set<std::string>& known) const {
    std::vector<std::string> out;
    const std::string prefix = section + ".";
    for (const auto& [key, value] : values_) {
        if (key.compare(0, prefix.size(), prefix) != 0) continue;
        if (!known.count(key.substr(prefix.size()))) out.push_back(key);
    }
    return out;
}

void GiSettings::requireKnown(const std::string& section,
                              const std::set<std::string>& known) const {
    auto unknown = unknownKeys(section, known);
    if (unknown.empty()) return;
    std::string list;
    for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
    throw InputError("gi." + unknown.front() + ": unknown setting (known: " + list + ")");
}

}  // namespace voxgi
