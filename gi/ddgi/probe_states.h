// Probe states and relocation from the probe rays (RTXGI's relocation and classification,
// seed 004's ALIVE / SLEEPING / DEAD), with an optional geometry query (e.g. the voxel
// occupancy of volumes/) that can turn probes off or put them to sleep without rays.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "gi/ddgi/probe_field.h"
#include "gi/ddgi/probe_rays.h"

namespace voxgi {

// Hooks for a geometry volume; empty functions are not used.
struct GeometryQuery {
    std::function<bool(glm::vec3)> insideSolid;          // true inside closed geometry
    std::function<float(glm::vec3)> distanceToGeometry;  // metres to the nearest surface
};

struct ProbeStateCounts {
    int active = 0, sleeping = 0, off = 0;
};

// What each probe traces this frame: active probes everything; sleeping probes everything
// every sleepInterval frames (staggered by index), else only the fixed rays, or nothing when
// `occupancyKnown` (a distanceToGeometry query: the occupancy, not rays, keeps telling that
// no geometry is near, and the probe's full updates re-classify it); off probes only the fixed
// rays. Without classification every probe traces everything.
std::vector<ProbeWork> scheduleProbes(const ProbeField& field, std::uint32_t frame, bool occupancyKnown = false);

// Moves probes that see too many backfaces (inside a wall) through the nearest backface, and
// probes closer than minFrontfaceDistance to a wall away from it; at most 0.45 cells per axis.
void relocateProbes(ProbeField& field, const RaySet& rays, const ProbeTrace& trace);

// Off: fixed-ray backface ratio above the threshold, or insideSolid. Active: a fixed ray hits a
// front face within one cell on every axis, or distanceToGeometry is within a cell diagonal.
// Otherwise sleeping. Probes that wake up from off start fresh (no hysteresis).
void classifyProbes(ProbeField& field, const RaySet& rays, const ProbeTrace& trace, const GeometryQuery& query);

ProbeStateCounts countStates(const ProbeField& field);

}  // namespace voxgi
