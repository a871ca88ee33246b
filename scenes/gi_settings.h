// The `gi` block of a scene: flat "section.key" -> value text, overridable from the command
// line (`--set lpv.steps=16`). Each technique reads its own keys with defaults, and asks for the
// keys it does not know so a typo is an error rather than a silent default.
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

    // Typed reads; a present value that does not parse raises InputError naming the key.
    std::string getString(const std::string& key, const std::string& fallback) const;
    int getInt(const std::string& key, int fallback) const;
    float getFloat(const std::string& key, float fallback) const;
    bool getBool(const std::string& key, bool fallback) const;

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
