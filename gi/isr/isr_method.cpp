// The `isr` method as the tools see it: settings, plan and presets (seed 003, docs/isr.md).
#include <cmath>
#include <string>

#include "gi/isr/isr_desc.h"
#include "gi/isr/isr_technique.h"
#include "gi/method.h"
#include "gi/methods.h"

namespace voxgi {

namespace {
// The far field's method, or null for none.
const MethodInfo* farFieldInfo(const IsrDesc& d) {
    return d.farField.empty() ? nullptr : &findMethod(d.farField);
}
}  // namespace

MethodInfo isrMethod() {
    MethodInfo m;
    m.name = "isr";
    m.summary = "image-space radiosity: one bounce of the direct light between on-screen surfaces, and AO (seed 003); a volume method may add the far field";
    declareSettings(m, isrSettings());
    // The far field's settings and memory are the far-field method's own (its section).
    m.validate = [](const GiSettings& gi) {
        if (const MethodInfo* far = farFieldInfo(readIsrDesc(gi))) far->validate(gi);
    };
    m.memoryBytes = [](const GiSettings& gi) {
        const MethodInfo* far = farFieldInfo(readIsrDesc(gi));
        return far && far->memoryBytes ? far->memoryBytes(gi) : 0.0;
    };
    m.create = [](const Scene& s) {
        const IsrDesc d = readIsrDesc(s.gi);
        std::unique_ptr<GiTechnique> far;
        if (const MethodInfo* info = farFieldInfo(d)) far = createTechnique(info->name, s);
        return std::make_unique<IsrTechnique>(d, std::move(far));
    };
    m.plan = [](const Scene& s) {
        const IsrDesc d = readIsrDesc(s.gi);
        TechniquePlan p;
        if (const MethodInfo* far = farFieldInfo(d)) {
            // The far field runs its own passes first: its light is what the patches send on.
            p = far->plan(s);
            p.notes.push_back("isr: far field " + far->name +
                              ", added where the screen's patches leave the hemisphere open and sent on by them");
        }
        if (s.triangleCount() == 0) {
            for (const char* pass : {"isr.downsample", "isr.gather", "isr.temporal", "isr.blur", "isr.apply"})
                p.skipped.push_back({pass, "no triangles: no surfaces to bounce between"});
            return p;
        }
        const std::string f = std::to_string(d.downsample);
        p.apply.push_back({"isr.downsample", "G-buffer and direct light to coarse patches of " + f + "x" + f + " pixels"});
        p.apply.push_back({"isr.gather", std::to_string(d.patches) + " sender patches per coarse pixel, one bounce and " +
                                             (d.farField.empty() ? "sphere occlusion" : "disc occlusion (the far field's weight)")});
        if (d.temporalFrames > 1)
            p.apply.push_back({"isr.temporal", "gathers averaged over up to " + std::to_string(d.temporalFrames) +
                                                   " frames where reprojection finds the same surface"});
        else p.skipped.push_back({"isr.temporal", "isr.temporal_frames=1"});
        if (d.blur > 0) p.apply.push_back({"isr.blur", "separable depth-aware blur, radius " + std::to_string(d.blur)});
        else p.skipped.push_back({"isr.blur", "isr.blur=0"});
        p.apply.push_back({"isr.apply", "bilateral upsample into the indirect layer"});
        p.guardBand = d.guardBand;
        if (d.guardBand > 0.0f)
            p.notes.push_back("isr: the frame is drawn " + std::to_string(int(std::lround(100.0 * d.guardBand))) +
                              " % of its size beyond each edge (isr.guard_band); surfaces there send light too");
        p.notes.push_back("isr: only surfaces on screen send light, with no visibility between them (seed 003)");
        return p;
    };
    m.presets = {{"low", {{"isr.patches", "16"}, {"isr.downsample", "4"}}},
                 {"medium", {{"isr.patches", "48"}, {"isr.downsample", "2"}}},
                 {"high", {{"isr.patches", "128"}, {"isr.downsample", "1"}}}};
    return m;
}

}  // namespace voxgi
