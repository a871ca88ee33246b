// The `isr` method as the tools see it: settings, plan and presets (seed 003, docs/isr.md).
#include <string>

#include "gi/isr/isr_desc.h"
#include "gi/isr/isr_technique.h"
#include "gi/method.h"

namespace voxgi {

MethodInfo isrMethod() {
    MethodInfo m;
    m.name = "isr";
    m.summary = "image-space radiosity: one bounce of the direct light between on-screen surfaces, and AO (seed 003)";
    declareSettings(m, isrSettings());
    m.create = [](const Scene& s) { return std::make_unique<IsrTechnique>(s, readIsrDesc(s.gi)); };
    m.plan = [](const Scene& s) {
        const IsrDesc d = readIsrDesc(s.gi);
        TechniquePlan p;
        if (s.triangleCount() == 0) {
            for (const char* pass : {"isr.downsample", "isr.gather", "isr.temporal", "isr.blur", "isr.apply"})
                p.skipped.push_back({pass, "no triangles: no surfaces to bounce between"});
            return p;
        }
        const std::string f = std::to_string(d.downsample);
        p.apply.push_back({"isr.downsample", "G-buffer and direct light to coarse patches of " + f + "x" + f + " pixels"});
        p.apply.push_back({"isr.gather", std::to_string(d.patches) + " sender patches per coarse pixel, one bounce and sphere occlusion"});
        if (d.temporalFrames > 1)
            p.apply.push_back({"isr.temporal", "gathers averaged over up to " + std::to_string(d.temporalFrames) +
                                                   " frames where reprojection finds the same surface"});
        else p.skipped.push_back({"isr.temporal", "isr.temporal_frames=1"});
        if (d.blur > 0) p.apply.push_back({"isr.blur", "separable depth-aware blur, radius " + std::to_string(d.blur)});
        else p.skipped.push_back({"isr.blur", "isr.blur=0"});
        p.apply.push_back({"isr.apply", "bilateral upsample into the indirect layer"});
        p.notes.push_back("isr: only surfaces on screen send light, with no visibility between them (seed 003)");
        return p;
    };
    m.presets = {{"low", {{"isr.patches", "16"}, {"isr.downsample", "4"}}},
                 {"medium", {{"isr.patches", "48"}, {"isr.downsample", "2"}}},
                 {"high", {{"isr.patches", "128"}, {"isr.downsample", "1"}}}};
    return m;
}

}  // namespace voxgi
