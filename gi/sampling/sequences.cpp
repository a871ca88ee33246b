#include "gi/sampling/sequences.h"

#include <cmath>

#include "shaders/shared/constants.h"

namespace voxgi {

glm::dvec2 r2Step() { return {0.75487766624669276005, 0.56984029099805326591}; }

glm::vec2 r2Sequence(int index, glm::vec2 offset) {
    glm::dvec2 v = glm::dvec2(offset) + double(index) * r2Step();
    return glm::vec2(v - glm::floor(v));
}

float radicalInverse2(unsigned bits) {
    bits = (bits << 16u) | (bits >> 16u);
    bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
    bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
    bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
    bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
    return float(double(bits) * 2.3283064365386963e-10);
}

glm::vec3 sphericalFibonacci(int index, int count) {
    const double goldenAngle = shading::kPiDouble * (3.0 - std::sqrt(5.0));
    double z = 1.0 - (2.0 * double(index) + 1.0) / double(count);
    double r = std::sqrt((1.0 - z * z > 0.0 ? 1.0 - z * z : 0.0));
    double phi = goldenAngle * double(index);
    return glm::vec3(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z));
}

}  // namespace voxgi
