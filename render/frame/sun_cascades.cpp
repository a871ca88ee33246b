#include "render/frame/sun_cascades.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace voxgi {

namespace {

// The smallest sphere around the piece of a symmetric view frustum between distances a < b
// along its axis, whose corners lie k times their distance off the axis: its centre's distance
// along the axis and its radius. It depends on the lens alone, so camera turns and moves leave
// it, and the texel size it sets, unchanged.
glm::vec2 sliceSphere(float a, float b, float k) {
    // Equidistant from a near and a far corner: (z - a)^2 + (a k)^2 = (b - z)^2 + (b k)^2.
    const float z = std::min(0.5f * (a + b) * (1.0f + k * k), b);
    const float radius = std::max(std::sqrt((z - a) * (z - a) + a * a * k * k), b * k);
    return {z, radius};
}

}  // namespace

SunCascades fitSunCascades(const Camera& camera, glm::vec3 direction, const Bounds& bounds, int mapSize, int count) {
    SunCascades out;
    direction = glm::normalize(direction);
    const glm::vec3 center = bounds.valid() ? bounds.center() : glm::vec3(0.0f);
    const float sceneRadius = bounds.valid() ? std::max(0.5f * glm::length(bounds.extent()), 1e-6f) : 1.0f;

    // Light space: a rotation fixed by the light alone, so the texel grid stays put in the world.
    const glm::vec3 up = std::abs(direction.y) < 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    const glm::mat4 lightView = glm::lookAt(glm::vec3(0.0f), direction, up);
    out.worldToLight = glm::transpose(glm::mat3(glm::vec3(lightView[0][0], lightView[1][0], lightView[2][0]),
                                                glm::vec3(lightView[0][1], lightView[1][1], lightView[2][1]), direction));
    // Depth covers the whole scene: casters between the sun and a slice lie outside the view.
    float nearDepth = 1e30f, farDepth = -1e30f;
    for (int i = 0; i < 8; ++i) {
        const glm::vec3 corner((i & 1) ? bounds.max.x : bounds.min.x, (i & 2) ? bounds.max.y : bounds.min.y,
                               (i & 4) ? bounds.max.z : bounds.min.z);
        const float d = glm::dot(bounds.valid() ? corner : center, direction);
        nearDepth = std::min(nearDepth, d);
        farDepth = std::max(farDepth, d);
    }
    const float margin = 1e-3f * sceneRadius;  // casters exactly on the bounds stay inside the map
    nearDepth -= margin;
    farDepth += margin;
    out.depthRange = farDepth - nearDepth;

    // The view's range: the camera sees nothing of the scene beyond its far plane or beyond the
    // far side of the scene's bounding sphere.
    const float nearPlane = std::max(camera.nearPlane, 1e-6f * sceneRadius);
    float farPlane = std::min(camera.farPlane, glm::length(camera.eye - center) + sceneRadius);
    farPlane = std::exp2(std::ceil(4.0f * std::log2(std::max(farPlane, 1e-30f))) / 4.0f);
    farPlane = std::max(farPlane, 2.0f * nearPlane);

    const float tanY = std::tan(0.5f * glm::radians(camera.fovYDegrees));
    const float k = tanY * std::sqrt(1.0f + camera.aspect() * camera.aspect());
    const glm::vec3 forward = glm::normalize(camera.target - camera.eye);
    count = std::max(count, 1);
    float sliceNear = nearPlane;
    for (int i = 1; i <= count; ++i) {
        const float f = float(i) / float(count);
        const float logSplit = nearPlane * std::pow(farPlane / nearPlane, f);
        const float uniformSplit = nearPlane + (farPlane - nearPlane) * f;
        const float sliceFar = i == count ? farPlane : kCascadeLogWeight * logSplit + (1.0f - kCascadeLogWeight) * uniformSplit;
        const glm::vec2 sphere = sliceSphere(sliceNear, sliceFar, k);
        const float radius = sphere.y;
        const float texel = 2.0f * radius / float(mapSize);
        // The sphere's centre in light space, snapped to the texel grid.
        const glm::vec3 c = out.worldToLight * (camera.eye + forward * sphere.x);
        const glm::vec2 snapped = glm::floor(glm::vec2(c) / texel + 0.5f) * texel;
        // glm::ortho looks down -z: light-space depth d is view z = -d.
        const glm::mat4 proj = glm::ortho(snapped.x - radius, snapped.x + radius, snapped.y - radius, snapped.y + radius,
                                          nearDepth, farDepth);
        const glm::mat4 bias = glm::translate(glm::mat4(1.0f), glm::vec3(0.5f)) * glm::scale(glm::mat4(1.0f), glm::vec3(0.5f));
        SunCascade cascade;
        cascade.worldToMap = bias * proj * lightView;
        cascade.texelWorld = texel;
        cascade.splitFar = sliceFar;
        out.cascades.push_back(cascade);
        sliceNear = sliceFar;
    }
    return out;
}

}  // namespace voxgi
