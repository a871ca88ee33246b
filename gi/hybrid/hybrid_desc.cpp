#include "gi/hybrid/hybrid_desc.h"

#include "gi/hybrid/mirror_paths.h"

namespace voxgi {

const SettingsTable<HybridDesc>& hybridSettings() {
    static const SettingsTable<HybridDesc> table = [] {
        using D = HybridDesc;
        SettingsTable<D> t("hybrid");
        t.choice("diffuse", &D::diffuse,
                 std::vector<std::pair<std::string, std::string>>{
                     {"clpv", "clpv"}, {"lpv", "lpv"}, {"ddgi", "ddgi"}, {"none", ""}},
                 "diffuse GI method lighting the rasterized surfaces and those seen in mirrors and through glass")
            .main();
        t.integer("depth", &D::depth, 1, 8, "mirror-like scatterings (reflections, refractions) followed from a pixel").main();
        t.number("glossy_roughness", &D::glossyRoughness, 0.0, 1.0,
                 "perceptual roughness up to which coats' and metals' GGX reflections are traced (0: mirrors only)")
            .main();
        t.integer("glossy_rays", &D::glossyRays, 1, kMaxGlossyRays, "rays per glossy pixel and frame");
        t.integer("denoise_radius", &D::denoiseRadius, 0, 8,
                  "half width in pixels of the edge-aware filter of glossy reflections (0: off)");
        t.flag("overlap", &D::overlap,
               "trace the next frame's rays on the CPU while the GPU lights this one (reflections one frame late)");
        t.flag("replay_bare", &D::replayBare,
               "benchmarks: trace each frame's rays again through bare Embree and report both rates (doubles the tracing; "
               "not with overlap)");
        return t;
    }();
    return table;
}

HybridDesc readHybridDesc(const GiSettings& gi) { return hybridSettings().read(gi); }

}  // namespace voxgi
