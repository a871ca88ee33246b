// Real spherical harmonics, 2 bands (4 coefficients) and 3 bands (9, for the sky), with the
// clamped-cosine lobe projection. The same constants live in shaders/common/sh.glsl; a test
// compares the two.
//
// Basis order and signs (the usual real SH, Sloan's convention):
//   Y0 = Y00  = 1 / (2 sqrt(pi))            = 0.282094792
//   Y1 = Y1-1 = -sqrt(3 / (4 pi)) * y       = -0.488602512 y
//   Y2 = Y10  =  sqrt(3 / (4 pi)) * z
//   Y3 = Y11  = -sqrt(3 / (4 pi)) * x
// The projection of max(0, dot(n, w)) is  A_l * Y_lm(n)  with A_0 = pi, A_1 = 2 pi / 3, A_2 = pi / 4.
#pragma once

#include <array>

#include <glm/glm.hpp>

#include "shaders/shared/constants.h"

namespace voxgi::sh {

constexpr float kY00 = 0.282094791773878f;   // 1 / (2 sqrt(pi))
constexpr float kY1 = 0.488602511902920f;    // sqrt(3 / (4 pi))
constexpr float kCosLobe0 = shading::kPi;             // A_0
constexpr float kCosLobe1 = 2.0f * shading::kPi / 3.0f;  // A_1
constexpr float kCosLobe2 = shading::kPi / 4.0f;         // A_2

struct Sh4 {
    std::array<float, 4> c{0.0f, 0.0f, 0.0f, 0.0f};

    Sh4& operator+=(const Sh4& o) {
        for (int i = 0; i < 4; ++i) c[std::size_t(i)] += o.c[std::size_t(i)];
        return *this;
    }
    Sh4 operator*(float s) const {
        Sh4 r = *this;
        for (float& v : r.c) v *= s;
        return r;
    }
    float operator[](int i) const { return c[std::size_t(i)]; }
};

// The basis functions at a unit direction.
inline Sh4 basis(glm::vec3 w) { return Sh4{{kY00, -kY1 * w.y, kY1 * w.z, -kY1 * w.x}}; }

inline float dot(const Sh4& a, const Sh4& b) {
    return a.c[0] * b.c[0] + a.c[1] * b.c[1] + a.c[2] * b.c[2] + a.c[3] * b.c[3];
}

// Value of the function in direction w.
inline float evaluate(const Sh4& f, glm::vec3 w) { return dot(f, basis(w)); }

// Coefficients of max(0, dot(n, w)) (unit n). Its integral over the sphere is pi.
inline Sh4 cosineLobe(glm::vec3 n) {
    Sh4 y = basis(n);
    return Sh4{{kCosLobe0 * y.c[0], kCosLobe1 * y.c[1], kCosLobe1 * y.c[2], kCosLobe1 * y.c[3]}};
}

// Integral of f(w) * max(0, dot(n, w)) over the sphere: the cosine-weighted convolution.
inline float convolveCosine(const Sh4& f, glm::vec3 n) {
    Sh4 y = basis(n);
    return kCosLobe0 * f.c[0] * y.c[0] + kCosLobe1 * (f.c[1] * y.c[1] + f.c[2] * y.c[2] + f.c[3] * y.c[3]);
}

// Integral of f over the sphere (for an intensity distribution: the total flux).
inline float integral(const Sh4& f) { return f.c[0] * (4.0f * shading::kPi * kY00); }

// 3 bands (9 coefficients), for skies.
struct Sh9 {
    std::array<float, 9> c{};
};
Sh9 basis9(glm::vec3 w);
float evaluate(const Sh9& f, glm::vec3 w);
// Irradiance-style convolution with max(0, dot(n, w)).
float convolveCosine(const Sh9& f, glm::vec3 n);

}  // namespace voxgi::sh
