// A technique's settings declared once (RTXGI's documented Desc defaults, Capsaicin's technique
// options): one row per key with the struct member it fills, its range or choices and a one-line
// doc; the default is the member's value in the default-constructed struct. Reading the scene's
// `gi` block and `--set`, `voxgi methods`, the viewer's widgets, the docs' settings tables and
// the tests that walk every range all come from the same rows (SettingInfo).
#pragma once

#include <functional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "scenes/gi_settings.h"

namespace voxgi {

enum class SettingKind { Integer, Number, Flag, Choice, Triple };

// One setting as the tools see it, whatever struct it fills.
struct SettingInfo {
    std::string key;                   // full key, "section.name"
    SettingKind kind = SettingKind::Number;
    double min = 0.0, max = 0.0;       // Integer, Number, Triple (each component); inclusive
    int step = 1;                      // Integer: the values are min + k * step
    bool whole = false;                // Triple: whole numbers only
    std::string fitWord;               // Triple, Integer: this word leaves it to be fitted
    std::vector<std::string> choices;  // Choice
    std::string defaultText;
    std::string doc;
    bool main = false;                 // one of the few settings a viewer shows first

    std::string rangeText() const;     // "[0, 100000]", "cpu | gl", "multiple of 4 in [8, 256]", ...
};

// Parsers for one value of `info` (InputError "gi.KEY: ..." when the text does not parse or is
// out of range). A Triple is "x,y,z", "x y z" or one value for all three; its fit word gives 0.
// An Integer's fit word gives kFittedInteger (its range starts at 0 or above).
constexpr int kFittedInteger = -1;
int parseInteger(const SettingInfo& info, const std::string& text);
float parseNumber(const SettingInfo& info, const std::string& text);
bool parseFlag(const SettingInfo& info, const std::string& text);
std::size_t parseChoice(const SettingInfo& info, const std::string& text);
glm::vec3 parseTriple(const SettingInfo& info, const std::string& text);
// Any kind: InputError when `text` is not a value of `info`.
void validateSetting(const SettingInfo& info, const std::string& text);
std::string formatNumber(double v);
std::string formatTriple(glm::vec3 v);

// Throws InputError when `gi` holds a key of `section` that `settings` does not declare.
void requireDeclared(const GiSettings& gi, const std::string& section, const std::vector<SettingInfo>& settings);

template <typename Desc>
class SettingsTable {
public:
    explicit SettingsTable(std::string section) : section_(std::move(section)) {}

    const std::string& section() const { return section_; }

    SettingsTable& integer(const std::string& key, int Desc::*member, int min, int max, std::string doc,
                           int step = 1) {
        return integerOrFit(key, member, min, max, std::move(doc), "", step);
    }

    // A whole number in [min, max] (min >= 0), or `fitWord` for one the technique fits (stored
    // as kFittedInteger).
    SettingsTable& integerOrFit(const std::string& key, int Desc::*member, int min, int max, std::string doc,
                                std::string fitWord, int step = 1) {
        // kFittedInteger must lie outside the range.
        if (!fitWord.empty() && min <= kFittedInteger)
            throw std::logic_error(key + ": a fitted integer's range must start at 0 or above");
        SettingInfo info = make(key, SettingKind::Integer, std::move(doc));
        info.min = min;
        info.max = max;
        info.step = step;
        info.fitWord = std::move(fitWord);
        return add(info, [member](Desc& d, const SettingInfo& i, const std::string& t) { d.*member = parseInteger(i, t); },
                   [member, fit = info.fitWord](const Desc& d) {
                       return !fit.empty() && d.*member == kFittedInteger ? fit : std::to_string(d.*member);
                   });
    }

    SettingsTable& number(const std::string& key, float Desc::*member, double min, double max, std::string doc) {
        SettingInfo info = make(key, SettingKind::Number, std::move(doc));
        info.min = min;
        info.max = max;
        return add(info, [member](Desc& d, const SettingInfo& i, const std::string& t) { d.*member = parseNumber(i, t); },
                   [member](const Desc& d) { return formatNumber(d.*member); });
    }

    SettingsTable& flag(const std::string& key, bool Desc::*member, std::string doc) {
        SettingInfo info = make(key, SettingKind::Flag, std::move(doc));
        info.choices = {"true", "false"};
        return add(info, [member](Desc& d, const SettingInfo& i, const std::string& t) { d.*member = parseFlag(i, t); },
                   [member](const Desc& d) { return std::string(d.*member ? "true" : "false"); });
    }

    template <typename E>
    SettingsTable& choice(const std::string& key, E Desc::*member, std::vector<std::pair<std::string, E>> choices,
                          std::string doc) {
        SettingInfo info = make(key, SettingKind::Choice, std::move(doc));
        for (const auto& c : choices) info.choices.push_back(c.first);
        return add(
            info,
            [member, choices](Desc& d, const SettingInfo& i, const std::string& t) {
                d.*member = choices[parseChoice(i, t)].second;
            },
            [member, choices](const Desc& d) {
                for (const auto& c : choices)
                    if (c.second == d.*member) return c.first;
                return std::string("?");
            });
    }

    // Three numbers in [min, max] each, or `fitWord` for the fitted value (stored as zero).
    SettingsTable& triple(const std::string& key, glm::vec3 Desc::*member, double min, double max, std::string doc,
                          std::string fitWord = "") {
        SettingInfo info = make(key, SettingKind::Triple, std::move(doc));
        info.min = min;
        info.max = max;
        info.fitWord = std::move(fitWord);
        return add(info, [member](Desc& d, const SettingInfo& i, const std::string& t) { d.*member = parseTriple(i, t); },
                   [member, fit = info.fitWord](const Desc& d) {
                       return !fit.empty() && d.*member == glm::vec3(0.0f) ? fit : formatTriple(d.*member);
                   });
    }

    // Three whole numbers (counts) in [min, max] each, or `fitWord` (stored as zero).
    SettingsTable& counts(const std::string& key, glm::ivec3 Desc::*member, int min, int max, std::string doc,
                          std::string fitWord = "") {
        SettingInfo info = make(key, SettingKind::Triple, std::move(doc));
        info.min = min;
        info.max = max;
        info.whole = true;
        info.fitWord = std::move(fitWord);
        return add(
            info,
            [member](Desc& d, const SettingInfo& i, const std::string& t) { d.*member = glm::ivec3(parseTriple(i, t)); },
            [member, fit = info.fitWord](const Desc& d) {
                return !fit.empty() && d.*member == glm::ivec3(0) ? fit : formatTriple(glm::vec3(d.*member));
            });
    }

    // Marks the setting added last as one of the main ones.
    SettingsTable& main() {
        entries_.back().info.main = true;
        return *this;
    }

    // A rule across settings, run after every key is read; it throws InputError naming the key.
    SettingsTable& check(std::function<void(const Desc&)> rule) {
        checks_.push_back(std::move(rule));
        return *this;
    }

    // `defaults` with the section's keys of `gi` applied. InputError names the key of an unknown
    // setting, a value that does not parse or one out of its range.
    Desc read(const GiSettings& gi, const Desc& defaults = Desc{}) const {
        requireDeclared(gi, section_, info(defaults));
        Desc d = defaults;
        for (const Entry& e : entries_)
            if (gi.has(e.info.key)) e.parse(d, e.info, gi.getString(e.info.key, ""));
        for (const auto& rule : checks_) rule(d);
        return d;
    }

    std::vector<SettingInfo> info(const Desc& defaults = Desc{}) const {
        std::vector<SettingInfo> out;
        for (const Entry& e : entries_) {
            out.push_back(e.info);
            out.back().defaultText = e.print(defaults);
        }
        return out;
    }

private:
    using Parse = std::function<void(Desc&, const SettingInfo&, const std::string&)>;
    using Print = std::function<std::string(const Desc&)>;
    struct Entry {
        SettingInfo info;
        Parse parse;
        Print print;
    };

    SettingInfo make(const std::string& key, SettingKind kind, std::string doc) const {
        SettingInfo info;
        info.key = section_ + "." + key;
        info.kind = kind;
        info.doc = std::move(doc);
        return info;
    }

    SettingsTable& add(SettingInfo info, Parse parse, Print print) {
        entries_.push_back({std::move(info), std::move(parse), std::move(print)});
        return *this;
    }

    std::string section_;
    std::vector<Entry> entries_;
    std::vector<std::function<void(const Desc&)>> checks_;
};

}  // namespace voxgi
