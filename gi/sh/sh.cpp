#include "gi/sh/sh.h"

namespace voxgi::sh {

Sh9 basis9(glm::vec3 w) {
    const float x = w.x, y = w.y, z = w.z;
    Sh9 s;
    s.c = {kY00,
           -kY1 * y,
           kY1 * z,
           -kY1 * x,
           1.092548430592079f * x * y,
           -1.092548430592079f * y * z,
           0.315391565252520f * (3.0f * z * z - 1.0f),
           -1.092548430592079f * x * z,
           0.546274215296040f * (x * x - y * y)};
    return s;
}

float evaluate(const Sh9& f, glm::vec3 w) {
    Sh9 y = basis9(w);
    float v = 0.0f;
    for (std::size_t i = 0; i < 9; ++i) v += f.c[i] * y.c[i];
    return v;
}

float convolveCosine(const Sh9& f, glm::vec3 n) {
    Sh9 y = basis9(n);
    const float a[9] = {kCosLobe0, kCosLobe1, kCosLobe1, kCosLobe1, kCosLobe2,
                        kCosLobe2, kCosLobe2, kCosLobe2, kCosLobe2};
    float v = 0.0f;
    for (std::size_t i = 0; i < 9; ++i) v += a[i] * f.c[i] * y.c[i];
    return v;
}

}  // namespace voxgi::sh
