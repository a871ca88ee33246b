// Which DDGI probes trace and blend in a frame, and how much of their old value a blend keeps:
// one definition for the CPU schedule (gi/ddgi/probe_states.cpp, probe_blend.cpp) and the GPU's
// (shaders/ddgi/schedule.comp, ddgi.trace = volume, where the probe states live on the GPU).
#ifndef VOXGI_SHARED_PROBE_SCHEDULE_H
#define VOXGI_SHARED_PROBE_SCHEDULE_H

#include "language.h"

#ifdef __cplusplus
namespace voxgi::shading {
using namespace glm;
#endif

// Probe states (gi/ddgi/probe_field.h's ProbeState), as stored in the w of the GPU's probe data.
constexpr int kProbeActive = 0;    // updated every frame
constexpr int kProbeSleeping = 1;  // no geometry near: updated every sleep interval
constexpr int kProbeOff = 2;       // inside geometry: never updated, never sampled

// A probe's work in one frame (gi/ddgi/probe_rays.h's ProbeWork).
constexpr int kProbeWorkNone = 0;       // nothing traced
constexpr int kProbeWorkFixedOnly = 1;  // only the classification rays
constexpr int kProbeWorkFull = 2;       // classification and blend rays; the probe blends

// `blends`: blends since the probe's data was reset (0: fresh). A fresh probe that is not off
// gets its first data at once; a sleeping one wakes every `sleepInterval` frames, staggered by
// its index, and between wakes traces its classification rays only when no occupancy tells
// that geometry stays away (`occupancyKnown`). Without classification every probe blends.
inline int probeWork(bool classify, int state, int blends, int frame, int probe, int sleepInterval,
                     bool occupancyKnown) {
    if (!classify) return kProbeWorkFull;
    if (blends == 0 && state != kProbeOff) return kProbeWorkFull;
    if (state == kProbeOff) return kProbeWorkFixedOnly;
    if (state == kProbeSleeping) {
        if ((frame + probe) % sleepInterval == 0) return kProbeWorkFull;
        return occupancyKnown ? kProbeWorkNone : kProbeWorkFixedOnly;
    }
    return kProbeWorkFull;
}

// The blend's hysteresis: min(hysteresis, n / (n + 1)) after n blends, a running mean over the
// first blends, so a new or woken probe converges in about 1 / (1 - hysteresis) frames; 1 or
// more freezes a probe after its first data.
inline float probeHysteresis(float hysteresis, int blends) {
    if (hysteresis >= 1.0f) return blends > 0 ? 1.0f : 0.0f;
    float n = float(max(blends, 0));
    return min(hysteresis, n / (n + 1.0f));
}

// What a probe's classification rays found: how many were traced, how many hit a back face,
// and the nearest back and front hits (distance, unit direction; a distance of at least the
// miss distance when there was none).
struct ProbeHits {
    int traced;
    int backfaces;
    float closestBack;
    vec3 closestBackDir;
    float closestFront;
    vec3 closestFrontDir;
};

// RTXGI's relocation: a probe with more than `backfaceThreshold` of its rays on back faces is
// inside and steps through the nearest back face, half `minFront` beyond it; one whose nearest
// front face is closer than `minFront` steps away from it. The offset stays within 45 % of a
// cell on every axis.
inline vec3 relocatedOffset(vec3 offset, ProbeHits hits, float backfaceThreshold, float minFront, vec3 spacing) {
    vec3 moved = offset;
    if (float(hits.backfaces) / float(hits.traced) > backfaceThreshold) {
        moved += hits.closestBackDir * (hits.closestBack + 0.5f * minFront);
    } else if (hits.closestFront < minFront) {
        moved -= hits.closestFrontDir * (minFront - hits.closestFront);
    } else {
        return offset;
    }
    return clamp(moved, -0.45f * spacing, 0.45f * spacing);
}

// Classification: off inside geometry, active with geometry near, else sleeping.
inline int classifiedState(bool inside, bool near) { return inside ? kProbeOff : near ? kProbeActive : kProbeSleeping; }

// The GPU update's indirect dispatches (three uints each: groups in x, y, z), in this order; the
// schedule adds each blending probe to the job axis (y for the shading, z for the others).
constexpr int kDdgiDispatchShade = 0;
constexpr int kDdgiDispatchBlendIrradiance = 1;
constexpr int kDdgiDispatchBlendDistance = 2;
constexpr int kDdgiDispatchBorderIrradiance = 3;
constexpr int kDdgiDispatchBorderDistance = 4;
constexpr int kDdgiDispatches = 5;
// Its counters: probes that traced only their classification rays, then probes per state
// after classification (kDdgiCountStates + state).
constexpr int kDdgiCountFixedOnly = 0;
constexpr int kDdgiCountStates = 1;
constexpr int kDdgiCounters = 4;

#ifdef __cplusplus
}  // namespace voxgi::shading
#endif

#endif
