// Small scenes shared by the DDGI tests (built in code, no files needed).
#pragma once

#include <map>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "gi/ddgi/ddgi_desc.h"

#include "scenes/primitives.h"
#include "scenes/scene.h"

namespace voxgi::test {

// A DdgiDesc from `ddgi.*` keys (values as the scene files write them), through the reader.
inline DdgiDesc descFrom(const std::map<std::string, std::string>& keys) {
    GiSettings gi;
    for (const auto& [k, v] : keys) gi.set("ddgi." + k, v);
    return readDdgiDesc(gi);
}

// A closed box of size `size` seen from inside: every surface has albedo rho and emits le.
inline Scene furnaceBox(float rho, float le, float size = 2.0f) {
    Scene s;
    Material m;
    m.albedo = glm::vec3(rho);
    m.emission = glm::vec3(le);
    s.materials.push_back(m);
    s.meshes.push_back(makeBox(glm::scale(glm::mat4(1.0f), glm::vec3(size)), 0, true));
    s.camera.eye = glm::vec3(0.0f);
    s.camera.target = glm::vec3(0.0f, 0.0f, 1.0f);
    return s;
}

// Two 2 x 1 x 1 rooms along x, closed, split at x = 0 by a wall of the given thickness, a point
// light in the room at x < 0.
inline Scene twoRooms(float wallThickness = 0.02f) {
    Scene s;
    Material white;
    white.albedo = glm::vec3(0.7f);
    s.materials.push_back(white);
    s.meshes.push_back(makeBox(glm::scale(glm::mat4(1.0f), glm::vec3(4.0f, 1.0f, 1.0f)), 0, true));
    s.meshes.push_back(makeBox(glm::scale(glm::mat4(1.0f), glm::vec3(wallThickness, 1.0f, 1.0f)), 0, false));
    Light light;
    light.type = LightType::Point;
    light.position = glm::vec3(-1.0f, 0.2f, 0.0f);
    light.emission = glm::vec3(2.0f);
    s.lights.push_back(light);
    s.camera.eye = glm::vec3(-1.5f, 0.0f, 0.0f);
    return s;
}

// A floor with two blocks under a point light and a sky: varied light for scrolling tests.
inline Scene openYard() {
    Scene s;
    Material grey;
    grey.albedo = glm::vec3(0.6f, 0.5f, 0.4f);
    s.materials.push_back(grey);
    s.meshes.push_back(makeQuad({glm::vec3(-4, 0, 4), glm::vec3(4, 0, 4), glm::vec3(4, 0, -4), glm::vec3(-4, 0, -4)}, 0));
    s.meshes.push_back(makeBox(glm::translate(glm::mat4(1.0f), glm::vec3(0.7f, 0.5f, 0.3f)), 0));
    s.meshes.push_back(makeBox(glm::translate(glm::mat4(1.0f), glm::vec3(-1.2f, 0.3f, -0.8f)) *
                                   glm::scale(glm::mat4(1.0f), glm::vec3(0.6f)), 0));
    Light light;
    light.type = LightType::Point;
    light.position = glm::vec3(0.0f, 2.5f, 0.0f);
    light.emission = glm::vec3(5.0f);
    s.lights.push_back(light);
    s.sky.enabled = true;
    s.sky.radiance = glm::vec3(0.05f, 0.07f, 0.1f);
    s.camera.eye = glm::vec3(0.0f, 1.0f, 0.0f);
    return s;
}

}  // namespace voxgi::test
