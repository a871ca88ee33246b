#include "scenes/gi_settings.h"

#include <cerrno>
#include <cstdlib>

#include "scenes/errors.h"

namespace voxgi {

std::string GiSettings::getString(const std::string& key, const std::string& fallback) const {
    auto it = values_.find(key);
    return it == values_.end() ? fallback : it->second;
}

int GiSettings::getInt(const std::string& key, int fallback) const {
    auto it = values_.find(key);
    if (it == values_.end()) return fallback;
    const char* s = it->second.c_str();
    char* end = nullptr;
    errno = 0;
    long v = std::strtol(s, &end, 10);
    if (end == s || *end != '\0' || errno == ERANGE || v < -2147483647L || v > 2147483647L)
        throw InputError("gi." + key + ": expected an integer, got '" + it->second + "'");
    return int(v);
}

float GiSettings::getFloat(const std::string& key, float fallback) const {
    auto it = values_.find(key);
    if (it == values_.end()) return fallback;
    const char* s = it->second.c_str();
    char* end = nullptr;
    errno = 0;
    float v = std::strtof(s, &end);
    if (end == s || *end != '\0' || errno == ERANGE)
        throw InputError("gi." + key + ": expected a number, got '" + it->second + "'");
    return v;
}

bool GiSettings::getBool(const std::string& key, bool fallback) const {
    auto it = values_.find(key);
    if (it == values_.end()) return fallback;
    if (it->second == "true" || it->second == "1" || it->second == "on") return true;
    if (it->second == "false" || it->second == "0" || it->second == "off") return false;
    throw InputError("gi." + key + ": expected true or false, got '" + it->second + "'");
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
