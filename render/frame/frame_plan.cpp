#include "render/frame/frame_plan.h"

#include <sstream>


namespace voxgi {


FramePlan planFrame(const Scene& scene, const std::string& method, int frames) {
    FramePlan plan;
    plan.method = method;
    plan.frames = frames;
    auto add = [&](const std::string& n, const std::string& r) { plan.passes.push_back({n, r}); };
    auto skip = [&](const std::string& n, const std::string& r) { plan.skipped.push_back({n, r}); };
    add("gbuffer", std::to_string(scene.triangleCount()) + " triangles");
    int cube = 0, maps = 0;
    for (const Light& l : scene.lights) {
        if (l.type == LightType::Point || l.type == LightType::Quad) ++cube;
        else ++maps;
    }
    if (cube) add("shadow_cube", std::to_string(cube) + " point/area light(s), one sample each per frame");
    else skip("shadow_cube", "no point or area lights");
    if (maps) add("shadow_map", std::to_string(maps) + " spot/directional light(s)");
    else skip("shadow_map", "no spot or directional lights");
    if (!scene.lights.empty()) add("direct_light", "Lambert + GGX, physical light units");
    else skip("direct_light", "no lights");
    add("emission_sky", scene.sky.enabled ? "emitters and constant sky" : "emitters (no sky)");
    if (!scene.sky.enabled) skip("sky_volume", "no sky");
    if (!scene.hasGlossyOrRefractive()) skip("reflections", "no glossy or refractive material");
    if (method != "direct") add("gi_" + method, "indirect light from " + method);
    if (frames > 1) add("accumulate", std::to_string(frames) + " frames (pixel jitter, light samples)");
    return plan;
}

std::string FramePlan::describe() const {
    std::ostringstream out;
    out << "frame plan: method " << method << ", " << frames << " frame(s)\n";
    for (const auto& p : passes) out << "  + " << p.name << ": " << p.reason << "\n";
    for (const auto& p : skipped) out << "  - " << p.name << ": " << p.reason << "\n";
    return out.str();
}

}  // namespace voxgi
