// Injection of surfels into one cascade (CPU; seed 000 section 3.10.2).
//
// Light: a surfel reflecting flux Phi is a virtual point light of intensity
// (Phi / pi) max(0, n . w) (W/sr), projected to SH and summed into the cell containing the
// surfel shifted along its normal and toward the light (against self-lighting). The seed's
// surfel weight W = A_s / A_c is carried by the units: Phi already scales with the surfel area
// A_s, and the apply pass turns intensity into radiance by dividing by the cell face area A_c.
//
// Blockers: a surfel of area A_s covers the fraction A_s / A_c of a cell face. Its blocker is
// the cosine lobe about its normal, B(w) = (A_s / A_c) max(0, n . w) (scaled so 2-band SH
// reaches 1 along n); light travelling in direction t is stopped by B(-t), so a surface blocks
// the light that arrives on its front. Blockers of one source are summed; sources are merged by max.
#pragma once

#include <vector>

#include "gi/lpv/cascades.h"
#include "gi/lpv/light_volume.h"
#include "gi/lpv/surfels.h"

namespace voxgi {

struct InjectionOffsets {
    float normalCells = 0.5f;
    float lightCells = 0.25f;
};

// Adds the surfels' light; returns the flux injected (W, summed over colours) for diagnostics.
double injectLight(const SurfelSource& source, const InjectionOffsets& offsets, LightVolume& volume);
// The same into cascade `level` of `cascades`, each VPL split by its shares (cascades.h) between
// the cascade's ring and inner volumes (both placed like the cascade); returns the flux
// injected into both.
double injectLight(const SurfelSource& source, const InjectionOffsets& offsets,
                   const std::vector<CascadePlacement>& cascades, std::size_t level, LightVolume& ring,
                   LightVolume& inner);

// Adds one source's blockers into `scratch` (zeroed on entry, same placement as `volume`) and
// merges them into `volume` by max.
void injectBlockers(const SurfelSource& source, BlockerVolume& scratch, BlockerVolume& volume);

// The blocker SH of a fully covered face with normal n: 1 along n (2-band SH of the cosine lobe
// peaks at 3/4, hence the 4/3).
glm::vec4 fullBlocker(glm::vec3 n);

}  // namespace voxgi
