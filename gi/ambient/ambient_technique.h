// The ambient baseline: direct light plus a constant irradiance E (W/m^2 per colour) on every
// surface, E from the gi setting `ambient.irradiance` ("r g b", or one value for grey; default
// 0). `voxgi eval` fits E to a path-traced reference (ambient_fit.h), which makes it an oracle: it
// says whether a GI method beats "direct light plus the right amount of flat fill light".
#pragma once

#include <memory>

#include <glm/glm.hpp>

#include "gi/settings_table.h"
#include "gi/technique.h"

namespace voxgi {

struct AmbientDesc {
    glm::vec3 irradiance{0.0f};
};

const SettingsTable<AmbientDesc>& ambientSettings();

// Needs a current GL context.
std::unique_ptr<GiTechnique> createAmbientTechnique(const AmbientDesc& desc);

}  // namespace voxgi
