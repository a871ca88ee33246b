#include "gi/octahedral/octahedral.h"

#include <cmath>

namespace voxgi::oct {

namespace {
float signNotZero(float v) { return v >= 0.0f ? 1.0f : -1.0f; }
}  // namespace

glm::vec2 encode(glm::vec3 d) {
    float l1 = std::abs(d.x) + std::abs(d.y) + std::abs(d.z);
    if (!(l1 > 0.0f)) return glm::vec2(0.0f);
    glm::vec2 p = glm::vec2(d.x, d.y) / l1;
    if (d.z < 0.0f)
        p = glm::vec2((1.0f - std::abs(p.y)) * signNotZero(p.x), (1.0f - std::abs(p.x)) * signNotZero(p.y));
    return p;
}

glm::vec3 decode(glm::vec2 s) {
    glm::vec3 d(s.x, s.y, 1.0f - std::abs(s.x) - std::abs(s.y));
    if (d.z < 0.0f) {
        float x = d.x;
        d.x = (1.0f - std::abs(d.y)) * signNotZero(x);
        d.y = (1.0f - std::abs(x)) * signNotZero(d.y);
    }
    return glm::normalize(d);
}

glm::vec3 texelDirection(int x, int y, int interior) {
    glm::vec2 uv((float(x) + 0.5f) / float(interior), (float(y) + 0.5f) / float(interior));
    return decode(uv * 2.0f - 1.0f);
}

glm::vec2 tileCoordinate(glm::vec3 direction, int interior) {
    glm::vec2 uv = encode(direction) * 0.5f + 0.5f;
    return glm::vec2(1.0f) + glm::clamp(uv, 0.0f, 1.0f) * float(interior);
}

glm::ivec2 borderSource(int x, int y, int n) {
    bool left = x == 0, right = x == n + 1, bottom = y == 0, top = y == n + 1;
    if ((left || right) && (bottom || top)) return glm::ivec2(left ? n : 1, bottom ? n : 1);
    if (bottom || top) return glm::ivec2(n + 1 - x, bottom ? 1 : n);
    if (left || right) return glm::ivec2(left ? 1 : n, n + 1 - y);
    return glm::ivec2(x, y);
}

}  // namespace voxgi::oct
