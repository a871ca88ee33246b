#include "tools/args.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "scenes/errors.h"

namespace voxgi::cli {

std::vector<std::string> splitList(const std::string& text) {
    std::vector<std::string> out;
    std::stringstream in(text);
    std::string part;
    while (std::getline(in, part, ','))
        if (!part.empty()) out.push_back(part);
    return out;
}

Args::Args(const std::vector<std::string>& argv, const std::set<std::string>& valued,
           const std::set<std::string>& flags, const std::set<std::string>& repeatable) {
    for (std::size_t i = 0; i < argv.size(); ++i) {
        const std::string& a = argv[i];
        if (a.size() < 2 || a[0] != '-' || (a.size() > 1 && std::isdigit(static_cast<unsigned char>(a[1])))) {
            positional_.push_back(a);
            continue;
        }
        std::string name = a, inlineValue;
        bool hasInline = false;
        auto eq = a.find('=');
        if (a.rfind("--", 0) == 0 && eq != std::string::npos) {
            name = a.substr(0, eq);
            inlineValue = a.substr(eq + 1);
            hasInline = true;
        }
        if (flags.count(name)) {
            if (hasInline) throw InputError(name + ": takes no value");
            flags_.insert(name);
        } else if (valued.count(name)) {
            std::string v;
            if (hasInline) v = inlineValue;
            else if (i + 1 < argv.size()) v = argv[++i];
            else throw InputError(name + ": missing value");
            auto& slot = values_[name];
            if (!slot.empty() && !repeatable.count(name)) throw InputError(name + ": given more than once");
            slot.push_back(v);
        } else {
            throw InputError(name + ": unknown option (see --help)");
        }
    }
}

std::optional<std::string> Args::value(const std::string& name) const {
    auto it = values_.find(name);
    if (it == values_.end()) return std::nullopt;
    return it->second.back();
}

std::string Args::value(const std::string& name, const std::string& fallback) const {
    auto v = value(name);
    return v ? *v : fallback;
}

std::vector<std::string> Args::values(const std::string& name) const {
    auto it = values_.find(name);
    return it == values_.end() ? std::vector<std::string>{} : it->second;
}

int Args::integer(const std::string& name, int fallback, int min, int max) const {
    auto v = value(name);
    if (!v) return fallback;
    char* end = nullptr;
    errno = 0;
    long x = std::strtol(v->c_str(), &end, 10);
    if (end == v->c_str() || *end != '\0' || errno == ERANGE)
        throw InputError(name + ": expected an integer, got '" + *v + "'");
    if (x < min || x > max)
        throw InputError(name + ": " + *v + " is out of range [" + std::to_string(min) + ", " + std::to_string(max) + "]");
    return int(x);
}

std::vector<int> Args::integers(const std::string& name, const std::string& fallback, int min, int max) const {
    const std::string text = value(name, fallback);
    std::vector<int> out;
    for (const std::string& item : splitList(text)) {
        char* end = nullptr;
        errno = 0;
        const long x = std::strtol(item.c_str(), &end, 10);
        if (end == item.c_str() || *end != '\0' || errno == ERANGE || x < min || x > max)
            throw InputError(name + ": expected comma-separated integers in [" + std::to_string(min) + ", " +
                             std::to_string(max) + "], got '" + text + "'");
        out.push_back(int(x));
    }
    if (out.empty()) throw InputError(name + ": expected comma-separated integers, got '" + text + "'");
    return out;
}

double Args::number(const std::string& name, double fallback, double min, double max) const {
    auto v = value(name);
    if (!v) return fallback;
    char* end = nullptr;
    errno = 0;
    double x = std::strtod(v->c_str(), &end);
    if (end == v->c_str() || *end != '\0' || errno == ERANGE || !std::isfinite(x))
        throw InputError(name + ": expected a number, got '" + *v + "'");
    if (x < min || x > max) throw InputError(name + ": " + *v + " is out of range");
    return x;
}

std::string usageLine(const std::string& usage) {
    const std::size_t end = usage.find('\n');
    return (end == std::string::npos ? usage : usage.substr(0, end) + " ...") + " (see --help)";
}

void Args::requirePositional(std::size_t count, const std::string& usage) const {
    if (positional_.size() != count)
        throw InputError(std::string(positional_.size() < count ? "missing" : "unexpected") + " argument; usage: " +
                         usageLine(usage));
}

}  // namespace voxgi::cli
