// Probe-state hooks from the voxel occupancy of volumes/: a probe with no occupied voxel in
// the neighbourhood of its cell is far from geometry (it sleeps) without any ray telling so.
// Inside-solid stays with the rays: a signed distance calls the inside of a closed room
// "solid", which is where DDGI probes live.
#pragma once

#include <memory>

#include "gi/ddgi/probe_field.h"
#include "gi/ddgi/probe_states.h"

namespace voxgi {

class SparseGeometryVolume;
struct NanoGeometry;
class RayTracer;

// Voxelizes the scene at a quarter of the volume's smallest spacing with two levels (the
// coarser one half a cell).
std::shared_ptr<const SparseGeometryVolume> voxelizeForProbes(const Scene& scene, const ProbeVolume& volume);

// The tracer's scene voxelized for ddgi.trace = volume (ddgi.trace_voxels voxels per smallest
// probe spacing of every cascade) as the NanoVDB grids the GPU traces, with surface offsets.
NanoGeometry voxelizeForTracing(const RayTracer& tracer, const ProbeField& field);

// distanceToGeometry: 0 when an occupied voxel of the coarser level lies within one cell of p
// on every axis, else a distance beyond any cell diagonal of `volume`.
GeometryQuery occupancyQuery(std::shared_ptr<const SparseGeometryVolume> voxels, const ProbeVolume& volume);

}  // namespace voxgi
