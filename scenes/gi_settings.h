// The `gi` block of a scene: flat "section.key" -> value text, overridable from the command
// line (`--set section.key=value`). Each method reads its own section through its settings table
// (gi/settings_table.h), which parses and range-checks the values and refuses the keys it does
// not declare, so a typo is an error rather than a silent default.
#pragma once

#include <map>
#include <set>
#include <string>
#include <vector>

namespace voxgi {

class GiSettings {
public:
    void set(const std::string& key, const std::string& value) { values_[key] = value; }
    bool has(const std::string& key) const { return values_.count(key) != 0; }

    std::string getString(const std::string& key, const std::string& fallback) const;

    // Parses "section.key=value" (the `--set` syntax).
    void applyOverride(const std::string& assignment);

    // Keys under `section.` that are not in `known` (returned as full keys).
    std::vector<std::string> unknownKeys(const std::string& section,
                                         const std::set<std::string>& known) const;
    // Raises InputError for the first unknown key of `section`.
    void requireKnown(const std::string& section, const std::set<std::string>& known) const;

    const std::map<std::string, std::string>& values() const { return values_; }

private:
    std::map<std::string, std::string> values_;
};

}  // namespace voxgi
