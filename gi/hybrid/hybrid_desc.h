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
    // Glossy reflections: the GGX lobes of coats and metals up to this perceptual roughness are
    // traced too, by rays sampled from the lobe (below it the LPV glossy march and the lights'
    // GGX highlights stay). 0: mirror-like lobes only. At 0.3 (alpha 0.09) half of GGX's
    // sampled half vectors lie within atan(alpha) = 5 degrees of the normal, so half the rays
    // leave within about 10 degrees of the mirror direction.
    float glossyRoughness = 0.3f;
    // Rays per glossy pixel and frame (the frames average them; the denoiser smooths each frame).
    int glossyRays = 1;
    // Half width in pixels of the glossy reflections' edge-aware filter (depth, normal and
    // roughness stop it at edges); 0 leaves each pixel's rays alone. Mirrors are never filtered.
    int denoiseRadius = 3;
    // The rays of the next frame are traced on the CPU while the GPU lights this one (seed 002:
    // 42.6 ms a frame in parallel against 68 ms serial): each frame shows the reflections traced
    // from the previous frame's G-buffer (the first frame traces its own). A still camera sees
    // the same light; a moving one sees reflections one frame late. Off: every frame traces its
    // own rays before its deferred passes.
    bool overlap = false;
    // Benchmarks: each frame's rays are traced again through Embree alone (rtcIntersect1) and
    // both rates reported (stats hybrid.rays_per_s, hybrid.bare_rays_per_s), which doubles the
    // tracing time. Serial frames only (not with overlap).
    bool replayBare = false;
};

const SettingsTable<HybridDesc>& hybridSettings();
HybridDesc readHybridDesc(const GiSettings& gi);

}  // namespace voxgi
