// Image-space radiosity's settings (gi.isr.*; seed 003, docs/isr.md): defaults documented here.
#pragma once

#include <string>

#include "gi/settings_table.h"

namespace voxgi {

struct IsrDesc {
    int patches = 48;          // sender patches gathered per coarse pixel (the seed: 48 timed, 80 for quality)
    // The gather disc's radius, a fraction of the picture's height (a guard band does not widen
    // it). The whole screen (1) measured best on every scene (docs/isr.md): one bounce from the
    // surfaces on screen is already short.
    float radius = 1.0f;
    int downsample = 2;        // coarse pixels are this many pixels square (the seed: 2)
    int blur = 2;              // depth-aware blur radius of the coarse result, coarse pixels (0: none)
    // How much of the sphere occlusion (seed Eq. 26) removes from the gathered light: 0 keeps it
    // all, 1 removes the occluded fraction. It scales only ISR's own bounce, which has no
    // visibility between patches, and never adds light. 0 measured best on every scene: ISR
    // misses more light (off screen, later bounces) than its missing visibility adds (docs/isr.md).
    float aoStrength = 0.0f;
    // Gathers averaged per coarse pixel where reprojection into the previous frame finds the same
    // surface point (shaders/isr/temporal.comp); the kernels turn every frame, so n frames of p
    // patches approach one gather of n x p. 1: no history.
    int temporalFrames = 1;
    // A volume method for the light from off screen: its indirect light is added where the
    // screen's patches leave the hemisphere open (1 - occlusion) and is sent on by the patches
    // with their direct light, so on-screen surfaces bring all bounces, not only the first.
    // Its own settings stay in its section (gi.ddgi.*, gi.lpv.*). The method's name, empty for
    // none (docs/isr.md, "Far field").
    std::string farField;
    // The frame's guard band (TechniquePlan::guardBand): this fraction of the picture's width and
    // height is drawn beyond each edge too, so surfaces just off screen send light. A view filled
    // by one wall, or looking out of the Cornell box, has no lit sender on screen (docs/isr.md).
    // The frame draws (1 + 2 x band)^2 times the pixels: 1.56x at 0.125, the narrowest band
    // with which ISR beats direct light in at least 95 % of 100 views of every scene (seed 003's
    // protocol; 0.25 does too, at 2.25x the pixels and by an estimate past 1 ms at 1080p).
    float guardBand = 0.125f;
};

const SettingsTable<IsrDesc>& isrSettings();
IsrDesc readIsrDesc(const GiSettings& gi);

}  // namespace voxgi
