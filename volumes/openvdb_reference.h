// OpenVDB's own mesh rasterizer (tools::meshToVolume) as an independent reference: the
// benchmark baseline and the occupancy oracle the tests compare the voxelizer against.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "scenes/scene.h"

namespace voxgi {

struct MeshToVolumeRun {
    double seconds = 0.0;
    double cpuSeconds = 0.0;  // user + system time of the whole process during the call
    std::uint64_t activeVoxels = 0;
    std::uint64_t memoryBytes = 0;  // the grid's memUsage
    std::uint64_t leafCount = 0;    // 8^3 leaves (each holds 512 floats, active or not)
    double peakBytes = 0.0;         // PeakResidentMemory over the call (NaN where unknown)
};

// User + system CPU seconds this process has used so far (all threads).
double processCpuSeconds();

// The most resident memory a piece of work took above what the process held when it started:
// free heap is handed back to the system (malloc_trim) and Linux's high-water mark reset
// (/proc/self/clear_refs), then peakBytes() reads that mark (VmHWM) against the start. NaN
// where /proc does not allow it. Only one may be live at a time.
class PeakResidentMemory {
public:
    PeakResidentMemory();
    double peakBytes() const;

private:
    double startBytes_ = 0.0;
    bool valid_ = false;
};

// Unsigned distance field with the given half width (voxels) at the voxel size, voxel (i,j,k)
// covering [i, i+1] * h like the geometry volumes. Timing excludes gathering the arrays.
MeshToVolumeRun runMeshToUnsignedDistance(const Scene& scene, float voxelSize, float halfWidth);

// The voxels whose closed box the surface passes through, judged from OpenVDB's unsigned
// distance d at the voxel centre and the normal n of OpenVDB's closest triangle: the box
// meets that triangle's plane when d <= (h/2)(|nx| + |ny| + |nz|). Near edges and corners the
// closest plane is only an approximation, which the tests' IoU bound allows for.
std::vector<glm::ivec3> meshToVolumeSurfaceVoxels(const Scene& scene, float voxelSize);

}  // namespace voxgi
