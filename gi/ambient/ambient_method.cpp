// The `ambient` baseline as the tools see it: one setting, one pass, and the fit to the
// reference that makes it an oracle in eval.
#include <cstdio>

#include "gi/ambient/ambient_fit.h"
#include "gi/ambient/ambient_technique.h"
#include "gi/method.h"

namespace voxgi {

MethodInfo ambientMethod() {
    MethodInfo m;
    m.name = "ambient";
    m.summary = "baseline: direct light plus a constant irradiance (eval fits it to the reference: an oracle)";
    declareSettings(m, ambientSettings());
    m.create = [](const Scene& s) { return createAmbientTechnique(ambientSettings().read(s.gi)); };
    m.plan = [](const Scene& s) {
        const glm::vec3 e = ambientSettings().read(s.gi).irradiance;
        TechniquePlan p;
        if (e == glm::vec3(0.0f)) p.skipped.push_back({"ambient.apply", "ambient.irradiance is 0"});
        else p.apply.push_back({"ambient.apply", "diffuse albedo / pi x the constant irradiance"});
        return p;
    };
    // The rendered indirect light is linear in E: one render with E = 1 gives every pixel's
    // response, and the fit makes the mean equal the reference's.
    m.fitToReference = [](const RenderWith& render, const Image& reference) {
        const Image unit = render({{"ambient.irradiance", "1"}});
        const glm::vec3 e = fitAmbientIrradiance(*unit.find("indirect"), *reference.find("indirect"));
        char text[96];
        std::snprintf(text, sizeof text, "%.9g %.9g %.9g", e.x, e.y, e.z);
        return SettingList{{"ambient.irradiance", text}};
    };
    return m;
}

}  // namespace voxgi
