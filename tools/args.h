// A small strict command-line parser: known options only, typed values, one-line errors
// (InputError) that name the option.
#pragma once

#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace voxgi::cli {

// "a,b,,c" -> {"a", "b", "c"}: the comma lists of options like --methods and --sizes.
std::vector<std::string> splitList(const std::string& text);
// The first line of a usage text with a pointer to --help: errors stay on one line.
std::string usageLine(const std::string& usage);

class Args {
public:
    // `valued` options take one value ("-o out.exr" or "--width=512"); `flags` take none.
    // Options listed in `repeatable` may appear several times (e.g. --set).
    Args(const std::vector<std::string>& argv, const std::set<std::string>& valued,
         const std::set<std::string>& flags, const std::set<std::string>& repeatable = {});

    const std::vector<std::string>& positional() const { return positional_; }
    bool flag(const std::string& name) const { return flags_.count(name) != 0; }
    bool has(const std::string& name) const { return values_.count(name) != 0; }
    std::optional<std::string> value(const std::string& name) const;
    std::string value(const std::string& name, const std::string& fallback) const;
    std::vector<std::string> values(const std::string& name) const;
    int integer(const std::string& name, int fallback, int min, int max) const;
    // A comma list of integers in [min, max] (--resolutions 32,64), `fallback` when absent.
    std::vector<int> integers(const std::string& name, const std::string& fallback, int min, int max) const;
    double number(const std::string& name, double fallback, double min, double max) const;
    // Exactly `count` positional arguments, else InputError with `usage`.
    void requirePositional(std::size_t count, const std::string& usage) const;

private:
    std::vector<std::string> positional_;
    std::map<std::string, std::vector<std::string>> values_;
    std::set<std::string> flags_;
};

}  // namespace voxgi::cli
