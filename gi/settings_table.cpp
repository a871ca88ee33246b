#include "gi/settings_table.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "scenes/errors.h"

namespace voxgi {

namespace {

[[noreturn]] void refuse(const SettingInfo& info, const std::string& what) {
    throw InputError("gi." + info.key + ": " + what);
}

std::string quoted(const std::string& text) { return "'" + text + "'"; }

bool inRange(double v, const SettingInfo& info) { return v >= info.min && v <= info.max; }

// A whole number, or nullopt-like false when `text` is not one.
bool readLong(const std::string& text, long* out) {
    const char* s = text.c_str();
    char* end = nullptr;
    errno = 0;
    long v = std::strtol(s, &end, 10);
    if (end == s || *end != '\0' || errno == ERANGE) return false;
    *out = v;
    return true;
}

bool readFloat(const std::string& text, float* out) {
    const char* s = text.c_str();
    char* end = nullptr;
    errno = 0;
    float v = std::strtof(s, &end);
    if (end == s || *end != '\0' || errno == ERANGE || !std::isfinite(v)) return false;
    *out = v;
    return true;
}

}  // namespace

std::string formatNumber(double v) {
    // Whole numbers in full (100000, not 1e+05).
    if (v == std::floor(v) && std::abs(v) < 1e15) {
        char whole[32];
        std::snprintf(whole, sizeof whole, "%.0f", v);
        return whole;
    }
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9g", v);
    // Round trips of floats print as the short text people typed (0.1, not 0.100000001).
    for (int digits = 1; digits <= 9; ++digits) {
        char shorter[32];
        std::snprintf(shorter, sizeof shorter, "%.*g", digits, v);
        if (std::strtof(shorter, nullptr) == float(v)) return shorter;
    }
    return buf;
}

std::string formatTriple(glm::vec3 v) {
    if (v.x == v.y && v.y == v.z) return formatNumber(v.x);
    return formatNumber(v.x) + "," + formatNumber(v.y) + "," + formatNumber(v.z);
}

std::string SettingInfo::rangeText() const {
    std::string range = "[" + formatNumber(min) + ", " + formatNumber(max) + "]";
    switch (kind) {
        case SettingKind::Integer:
            return (step > 1 ? "multiple of " + std::to_string(step) + " in " + range : range) +
                   (fitWord.empty() ? "" : " or " + fitWord);
        case SettingKind::Number:
            return range;
        case SettingKind::Flag:
        case SettingKind::Choice: {
            std::string out;
            for (const std::string& c : choices) out += (out.empty() ? "" : " | ") + c;
            return out;
        }
        case SettingKind::Triple:
            return std::string(whole ? "whole numbers" : "numbers") + " in " + range + " (x,y,z or one)" +
                   (fitWord.empty() ? "" : " or " + fitWord);
    }
    return range;
}

int parseInteger(const SettingInfo& info, const std::string& text) {
    if (!info.fitWord.empty() && text == info.fitWord) return kFittedInteger;
    long v = 0;
    if (!readLong(text, &v)) refuse(info, "expected an integer, got " + quoted(text));
    if (!inRange(double(v), info) || (long(v) - long(info.min)) % info.step != 0)
        refuse(info, text + " is not " + (info.step > 1 ? "a " : "in ") + info.rangeText());
    return int(v);
}

float parseNumber(const SettingInfo& info, const std::string& text) {
    float v = 0.0f;
    if (!readFloat(text, &v)) refuse(info, "expected a finite number, got " + quoted(text));
    // Compared in float: "0.45" is in [0, 0.45] although 0.45f < 0.45.
    if (!(v >= float(info.min) && v <= float(info.max))) refuse(info, text + " is outside " + info.rangeText());
    return v;
}

bool parseFlag(const SettingInfo& info, const std::string& text) {
    if (text == "true" || text == "1" || text == "on") return true;
    if (text == "false" || text == "0" || text == "off") return false;
    refuse(info, "expected true or false, got " + quoted(text));
}

std::size_t parseChoice(const SettingInfo& info, const std::string& text) {
    for (std::size_t i = 0; i < info.choices.size(); ++i)
        if (info.choices[i] == text) return i;
    refuse(info, "expected " + info.rangeText() + ", got " + quoted(text));
}

glm::vec3 parseTriple(const SettingInfo& info, const std::string& text) {
    if (!info.fitWord.empty() && text == info.fitWord) return glm::vec3(0.0f);
    std::string spaced = text;
    for (char& c : spaced)
        if (c == ',') c = ' ';
    std::istringstream in(spaced);
    std::vector<float> values;
    std::string word;
    while (in >> word) {
        float v = 0.0f;
        if (!readFloat(word, &v) || values.size() == 3) refuse(info, "expected " + info.rangeText() + ", got " + quoted(text));
        values.push_back(v);
    }
    if (values.size() != 1 && values.size() != 3) refuse(info, "expected " + info.rangeText() + ", got " + quoted(text));
    glm::vec3 v = values.size() == 1 ? glm::vec3(values[0]) : glm::vec3(values[0], values[1], values[2]);
    for (int a = 0; a < 3; ++a) {
        if (!(v[a] >= float(info.min) && v[a] <= float(info.max)) || (info.whole && v[a] != std::floor(v[a])))
            refuse(info, text + " is not " + info.rangeText());
    }
    return v;
}

void validateSetting(const SettingInfo& info, const std::string& text) {
    switch (info.kind) {
        case SettingKind::Integer: parseInteger(info, text); return;
        case SettingKind::Number: parseNumber(info, text); return;
        case SettingKind::Flag: parseFlag(info, text); return;
        case SettingKind::Choice: parseChoice(info, text); return;
        case SettingKind::Triple: parseTriple(info, text); return;
    }
}

void requireDeclared(const GiSettings& gi, const std::string& section, const std::vector<SettingInfo>& settings) {
    std::set<std::string> known;
    for (const SettingInfo& s : settings) known.insert(s.key.substr(section.size() + 1));
    gi.requireKnown(section, known);
}

}  // namespace voxgi
