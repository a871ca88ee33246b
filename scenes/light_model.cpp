// shading::packLight: a scene Light in the layout of shaders/shared/light_model.h.
#include "shaders/shared/light_model.h"

#include <cmath>

#include "scenes/scene.h"

namespace voxgi::shading {

static_assert(int(LightType::Point) == kLightPoint && int(LightType::Spot) == kLightSpot &&
                  int(LightType::Directional) == kLightDirectional && int(LightType::Quad) == kLightQuad,
              "LightType and the shared light kinds agree");

PackedLight packLight(const Light& light) {
    PackedLight p;
    p.position = vec4(light.position, 0.0f);
    p.direction = vec4(0.0f);
    p.emission = vec4(light.emission, 0.0f);
    p.edgeU = vec4(0.0f);
    p.edgeV = vec4(0.0f);
    p.shape = vec4(0.0f);
    p.kind = ivec4(int(light.type), 0, 0, 0);
    switch (light.type) {
        case LightType::Point:
            break;
        case LightType::Spot:
            p.direction = vec4(normalize(light.direction), 0.0f);
            p.shape.x = std::cos(radians(light.outerConeDegrees));
            p.shape.y = std::cos(radians(light.innerConeDegrees));
            break;
        case LightType::Directional: {
            p.direction = vec4(normalize(light.direction), 0.0f);
            // 1 - cos(alpha) = 2 sin^2(alpha / 2), exact in float however small alpha is.
            const double s = std::sin(0.5 * 0.5 * double(light.angularDiameterDegrees) * kPiDouble / 180.0);
            p.shape.w = float(2.0 * s * s);
            break;
        }
        case LightType::Quad:
            p.direction = vec4(light.quadNormal(), 0.0f);
            p.edgeU = vec4(light.edgeU, 0.0f);
            p.edgeV = vec4(light.edgeV, 0.0f);
            p.shape.z = light.area();
            break;
    }
    return p;
}

}  // namespace voxgi::shading
