#include "render/frame/techniques.h"

#include "gi/ambient/ambient_technique.h"
#include "gi/lpv/lpv_technique.h"
#include "gi/ddgi/ddgi_technique.h"
#include "scenes/errors.h"

namespace voxgi {

namespace {
using Factory = std::unique_ptr<GiTechnique> (*)(const Scene&);

struct Entry {
    const char* name;
    Factory create;  // null: named by the design, not built yet
};

// One line per method.
const Entry kMethods[] = {
    {"direct", [](const Scene&) -> std::unique_ptr<GiTechnique> { return nullptr; }},
    {"ambient", createAmbient},
    {"lpv", createLpv},
    {"clpv", createClpv},
    {"ilpv", nullptr},
    {"ddgi", createDdgiTechnique},
    {"isr", nullptr},
    {"hybrid", nullptr},
};
}  // namespace

std::vector<std::string> builtMethods() {
    std::vector<std::string> out;
    for (const Entry& e : kMethods)
        if (e.create) out.push_back(e.name);
    return out;
}

std::vector<std::string> plannedMethods() {
    std::vector<std::string> out;
    for (const Entry& e : kMethods)
        if (!e.create) out.push_back(e.name);
    return out;
}

namespace {
const Entry& find(const std::string& method) {
    for (const Entry& e : kMethods) {
        if (method != e.name) continue;
        if (!e.create) throw NotImplementedError("method '" + method + "' is not implemented yet");
        return e;
    }
    std::string all;
    for (const Entry& e : kMethods) all += (all.empty() ? "" : ", ") + std::string(e.name);
    throw InputError("--method " + method + ": unknown method (known: " + all + ")");
}
}  // namespace

void validateMethod(const std::string& method) { find(method); }

std::unique_ptr<GiTechnique> createTechnique(const std::string& method, const Scene& scene) {
    return find(method).create(scene);
}

}  // namespace voxgi
