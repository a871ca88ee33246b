#include "render/frame/frame_plan.h"

#include <sstream>

#include "gi/methods.h"
#include "gi/sky/sky_volume.h"

namespace voxgi {

namespace {

bool hasEmission(const Scene& scene) {
    for (const Material& m : scene.materials)
        if (m.isEmissive()) return true;
    return false;
}

std::string lightCount(int n, const char* kinds) {
    return std::to_string(n) + " " + kinds + " light" + (n == 1 ? "" : "s");
}

}  // namespace

bool FramePlan::runs(const std::string& pass) const {
    for (const PlannedPass& p : passes)
        if (p.name == pass) return true;
    return false;
}

FramePlan planFrame(const Scene& scene, const std::string& method, int frames) {
    const MethodInfo& info = validateMethod(method, scene);
    FramePlan plan;
    plan.method = method;
    plan.frames = frames;
    plan.technique = info.plan(scene);
    auto add = [&](const std::string& n, const std::string& r) { plan.passes.push_back({n, r}); };
    auto skip = [&](const std::string& n, const std::string& r) { plan.skipped.push_back({n, r}); };

    if (scene.triangleCount() > 0) add("gbuffer", std::to_string(scene.triangleCount()) + " triangles");
    else skip("gbuffer", "no triangles: every pixel sees the sky");
    plan.passes.insert(plan.passes.end(), plan.technique.update.begin(), plan.technique.update.end());

    int cube = 0, maps = 0, suns = 0;
    for (const Light& l : scene.lights)
        (l.type == LightType::Point || l.type == LightType::Quad ? cube : l.type == LightType::Spot ? maps : suns) += 1;
    if (cube) add("shadow_cube", lightCount(cube, "point or area") + ": a distance cube map each per frame");
    else skip("shadow_cube", "no point or area lights");
    if (maps) add("shadow_map", lightCount(maps, "spot") + ": a depth map each");
    else skip("shadow_map", "no spot lights");
    if (suns) add("shadow_sun", lightCount(suns, "directional") + ": cascaded depth maps over the view each, soft by the sun's disc");
    else skip("shadow_sun", "no directional lights");
    if (!scene.lights.empty()) add("direct_light", "Lambert + GGX in physical units, one light at a time after its shadow");
    else skip("direct_light", "no lights");
    const bool emitters = hasEmission(scene), sky = scene.sky.enabled;
    if (!sky) skip("sky_light", "no sky");
    else if (scene.triangleCount() == 0) skip("sky_light", "no triangles");
    else if (const SkyVolumeDesc d = readSkyVolumeDesc(scene.gi); !d.light) skip("sky_light", "sky.light=false");
    else {
        add("sky_volume", "the sky's irradiance as 3-band SH, " + std::to_string(d.rays) + " Embree rays a cell, " +
                              std::to_string(d.resolution) + " cells along the longest side (the first frame)");
        add("sky_light", "that irradiance on every surface");
    }
    if (emitters || sky)
        add("emission_sky", std::string(emitters ? "emitters" : "") + (emitters && sky ? " and " : "") +
                                (sky ? "the sky behind the scene" : ""));
    else skip("emission_sky", "no emitters and no sky");
    plan.passes.insert(plan.passes.end(), plan.technique.apply.begin(), plan.technique.apply.end());
    plan.skipped.insert(plan.skipped.end(), plan.technique.skipped.begin(), plan.technique.skipped.end());

    plan.notes = plan.technique.notes;
    for (const Light& l : scene.lights)
        if (l.type == LightType::Quad) {
            plan.notes.push_back("area lights: one sample point per frame; the frames average them");
            break;
        }
    if (scene.hasGlossyOrRefractive() && !plan.runs("hybrid.trace"))
        plan.notes.push_back("glossy or refractive materials: the frame shades them with GGX from the lights; "
                             "reflections of the scene and refraction are not traced (--method hybrid traces mirror-like ones)");
    return plan;
}

std::string FramePlan::describe() const {
    std::ostringstream out;
    out << "frame plan: method " << method << ", " << frames << " frame(s)\n";
    for (const auto& p : passes) out << "  + " << p.name << ": " << p.reason << "\n";
    for (const auto& p : skipped) out << "  - " << p.name << ": " << p.reason << "\n";
    for (const auto& n : notes) out << "  note: " << n << "\n";
    return out.str();
}

}  // namespace voxgi
