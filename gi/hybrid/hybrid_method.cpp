// The `hybrid` method as the tools see it: settings, plan and presets (seed 002 chapter 6,
// docs/hybrid.md).
#include <string>

#include "gi/hybrid/hybrid_desc.h"
#include "gi/hybrid/hybrid_technique.h"
#include "gi/method.h"
#include "gi/methods.h"
#include "shaders/shared/material.h"

namespace voxgi {

MethodInfo clpvMethod();  // gi/lpv/lpv_method.cpp

namespace {
// The diffuse method's description, or null for none.
const MethodInfo* diffuseInfo(const HybridDesc& d) { return d.diffuse.empty() ? nullptr : &findMethod(d.diffuse); }

// Whether some material has a lobe the method traces (mirror-like, or glossy up to the setting).
bool hasTracedLobes(const Scene& s, const HybridDesc& d) {
    for (const Material& m : s.materials)
        if (shading::tracedLobe(m.roughness, m.metallic, m.specular, m.transmission, d.glossyRoughness)) return true;
    return false;
}
}  // namespace

MethodInfo hybridMethod() {
    MethodInfo m;
    m.name = "hybrid";
    m.summary = "rasterized frame + a diffuse GI method, mirror-like reflections and refractions traced with Embree (seed 002)";
    declareSettings(m, hybridSettings());
    m.validate = [](const GiSettings& gi) {
        if (const MethodInfo* d = diffuseInfo(readHybridDesc(gi))) d->validate(gi);
    };
    m.memoryBytes = [](const GiSettings& gi) {
        const MethodInfo* d = diffuseInfo(readHybridDesc(gi));
        return d && d->memoryBytes ? d->memoryBytes(gi) : 0.0;
    };
    m.create = [](const Scene& s) {
        const HybridDesc d = readHybridDesc(s.gi);
        std::unique_ptr<GiTechnique> diffuse;
        if (const MethodInfo* info = diffuseInfo(d)) diffuse = createTechnique(info->name, s);
        return createHybridTechnique(s, d, std::move(diffuse));
    };
    m.plan = [](const Scene& s) {
        const HybridDesc d = readHybridDesc(s.gi);
        TechniquePlan p;
        if (const MethodInfo* diffuse = diffuseInfo(d)) {
            p = diffuse->plan(s);
            p.notes.push_back("hybrid: diffuse light by " + diffuse->name + ", on the frame and on what mirrors and glass show");
        }
        if (!hasTracedLobes(s, d)) {
            for (const char* pass : {"hybrid.trace", "hybrid.upload", "hybrid.composite"})
                p.skipped.push_back({pass, "no mirror-like material (roughness^2 < 1e-3 with a coat, metal or transmission) "
                                           "and no coat or metal of roughness <= hybrid.glossy_roughness"});
            return p;
        }
        p.update.push_back({"hybrid.trace", "Embree rays from mirror-like pixels through up to " + std::to_string(d.depth) +
                                                " reflections and refractions, " + std::to_string(d.glossyRays) +
                                                " GGX-sampled ray(s) per glossy pixel (CPU)"});
        p.update.push_back({"hybrid.upload", "the surfaces they reach as layers of G-buffers"});
        p.apply.push_back({"hybrid.composite", "each layer's light times its Fresnel weight, and the emitters and sky the rays met; "
                                               "glossy pixels through an edge-aware filter"});
        p.notes.push_back("hybrid: the frame's direct light, sky light and the diffuse method also light each layer");
        return p;
    };
    // Eval's presets are the default diffuse method's (clpv low, medium, high, timed without
    // reuse), so each row compares with the clpv row of the same name.
    m.presets = clpvMethod().presets;
    m.benchVariants = {{"default", {}},
                       {"overlap", {{"hybrid.overlap", "true"}}},
                       {"embree-share", {{"hybrid.replay_bare", "true"}}}};
    return m;
}

}  // namespace voxgi
