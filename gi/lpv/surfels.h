// Surfels: small oriented patches that inject light (virtual point lights) and blockers into
// the light propagation volumes. They come from reflective shadow maps and the G-buffer.
#pragma once

#include <vector>

#include <glm/glm.hpp>

namespace voxgi {

struct Surfel {
    glm::vec3 position{0.0f};
    glm::vec3 normal{0.0f, 1.0f, 0.0f};
    glm::vec3 flux{0.0f};      // reflected diffuse flux, W (zero for blocker-only surfels)
    glm::vec3 albedo{0.0f};    // diffuse albedo (for extra bounces)
    glm::vec3 toLight{0.0f};   // unit direction toward the light (zero when not lit)
    float area = 0.0f;         // m^2
};

// One injection source (one RSM face, or the G-buffer): its blockers are summed inside the
// source and merged by max across sources (seed 000 section 3.10.2).
struct SurfelSource {
    std::vector<Surfel> surfels;
};

}  // namespace voxgi
