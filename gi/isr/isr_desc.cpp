#include "gi/isr/isr_desc.h"

namespace voxgi {

const SettingsTable<IsrDesc>& isrSettings() {
    static const SettingsTable<IsrDesc> table = [] {
        using D = IsrDesc;
        SettingsTable<D> t("isr");
        t.integer("patches", &D::patches, 1, 1024, "sender patches gathered per coarse pixel").main();
        t.number("radius", &D::radius, 0.001, 2.0,
                 "gather disc radius, a fraction of the picture's height (a guard band does not widen it)");
        t.integer("downsample", &D::downsample, 1, 8, "coarse pixels are this many pixels square");
        t.integer("blur", &D::blur, 0, 16, "depth-aware blur radius of the coarse result, in coarse pixels (0: none)");
        t.number("ao_strength", &D::aoStrength, 0.0, 1.0,
                 "fraction of the occlusion (spheres; discs with a far field) taken from ISR's own bounce (0: none; never adds light)");
        t.integer("temporal_frames", &D::temporalFrames, 1, 256,
                  "gathers averaged over frames where reprojection finds the same surface (1: none)");
        t.choice("far_field", &D::farField,
                 std::vector<std::pair<std::string, std::string>>{{"none", ""}, {"lpv", "lpv"}, {"clpv", "clpv"}, {"ddgi", "ddgi"}},
                 "volume method for the light from off screen, weighted by the hemisphere the screen leaves open");
        t.number("guard_band", &D::guardBand, 0.0, 1.0,
                 "fraction of the picture's width and height also drawn beyond each edge, as senders (0: none)");
        return t;
    }();
    return table;
}

IsrDesc readIsrDesc(const GiSettings& gi) { return isrSettings().read(gi); }

}  // namespace voxgi
