// The hybrid method's settings (gi.hybrid.*; seed 002 chapter 6, docs/hybrid.md): defaults
// documented here.
#pragma once

#include <string>

#include "gi/settings_table.h"

namespace voxgi {

struct HybridDesc {
    // The diffuse GI method whose light the rasterized surfaces and the surfaces seen in mirrors
    // and through glass get (its own settings stay in its section). Empty: direct light only.
    // Screen-space methods (isr) cannot light what only a mirror sees and are not offered.
    std::string diffuse = "clpv";
    // Mirror-like scatterings followed from a pixel's surface: 1 is the seed's one reflection;
    // seeing through a glass sphere takes 2 (in and out), a mirror in a mirror 2.
    int depth = 3;
    // Benchmarks: each frame's rays are traced again through Embree alone (rtcIntersect1) and
    // both rates reported (stats hybrid.rays_per_s, hybrid.bare_rays_per_s), which doubles the
    // tracing time.
    bool replayBare = false;
};

const SettingsTable<HybridDesc>& hybridSettings();
HybridDesc readHybridDesc(const GiSettings& gi);

}  // namespace voxgi
