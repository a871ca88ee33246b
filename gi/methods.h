// The method list: every GI method by name, built ones and the ones the design names but that
// are not built yet. Adding a method adds its folder under gi/ and one line in methods.cpp.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "gi/method.h"

namespace voxgi {

const std::vector<MethodInfo>& methods();
// InputError for an unknown name (listing the known ones), NotImplementedError for a planned one.
const MethodInfo& findMethod(const std::string& name);
std::vector<std::string> builtMethods();
std::vector<std::string> plannedMethods();

// findMethod + its settings validated against scene.gi (InputError naming the key). No GL.
const MethodInfo& validateMethod(const std::string& name, const Scene& scene);
// Null for a method without indirect light (direct). Needs a current GL context.
std::unique_ptr<GiTechnique> createTechnique(const std::string& name, const Scene& scene);

// Sets KEY=VALUE in the section of every built method that declares KEY (`--backend gl` sets
// lpv.backend and ddgi.backend); InputError when no method declares it or the value is refused.
void setForEveryMethod(GiSettings& gi, const std::string& key, const std::string& value);

}  // namespace voxgi
