// The GI methods the renderer can run, by name. Adding a method adds its folder under gi/ and
// one line in techniques.cpp.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "gi/technique.h"

namespace voxgi {

// Null for "direct" (no indirect light). Throws InputError for an unknown name and
// NotImplementedError for a method the design names but that is not built yet.
std::unique_ptr<GiTechnique> createTechnique(const std::string& method, const Scene& scene);

// Checks the name only (no GL needed): InputError or NotImplementedError as above.
void validateMethod(const std::string& method);

// Method names, built ones first.
std::vector<std::string> builtMethods();
std::vector<std::string> plannedMethods();

}  // namespace voxgi
