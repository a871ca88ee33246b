// The ambient baseline: direct light plus a constant irradiance E (W/m^2 per colour) on every
// surface, E read from the gi setting `ambient.irradiance` ("r g b", or one value for grey;
// default 0). `voxgi eval` fits E to a path-traced reference (ambient_fit.h) so that a GI method
// can be said to beat "direct light plus the right amount of flat fill light".
#pragma once

#include <memory>

#include <glm/glm.hpp>

#include "gi/technique.h"

namespace voxgi {

// Parses gi `ambient.irradiance`; InputError names the key on a malformed or negative value.
glm::vec3 readAmbientIrradiance(const GiSettings& gi);

std::unique_ptr<GiTechnique> createAmbient(const Scene& scene);

}  // namespace voxgi
