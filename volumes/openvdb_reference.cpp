#include "volumes/openvdb_reference.h"

#include <chrono>
#include <cmath>
#include <fstream>
#include <limits>
#include <string>

#include <malloc.h>
#include <sys/resource.h>

#include <openvdb/tools/MeshToVolume.h>

#include "volumes/detail/geometry_grids.h"
#include "volumes/detail/sdf_fill.h"
#include "volumes/openvdb_setup.h"

namespace voxgi {

double processCpuSeconds() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return double(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
           1e-6 * double(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

namespace {

// A "Name:   N kB" line of /proc/self/status in bytes, or NaN.
double procStatusBytes(const std::string& name) {
    std::ifstream in("/proc/self/status");
    std::string line;
    while (std::getline(in, line))
        if (line.compare(0, name.size() + 1, name + ":") == 0) return 1024.0 * std::stod(line.substr(name.size() + 1));
    return std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

PeakResidentMemory::PeakResidentMemory() {
    malloc_trim(0);
    std::ofstream reset("/proc/self/clear_refs");
    reset << "5";
    reset.flush();
    valid_ = bool(reset);
    startBytes_ = procStatusBytes("VmRSS");
}

double PeakResidentMemory::peakBytes() const {
    return valid_ ? procStatusBytes("VmHWM") - startBytes_ : std::numeric_limits<double>::quiet_NaN();
}

MeshToVolumeRun runMeshToUnsignedDistance(const Scene& scene, float voxelSize, float halfWidth) {
    initializeOpenVdb();
    detail::MeshArrays arrays = detail::collectMeshArrays(scene);
    std::vector<openvdb::Vec4I> quads;
    auto xform = detail::voxelTransform(voxelSize);
    const PeakResidentMemory memory;
    const double cpuStart = processCpuSeconds();
    auto start = std::chrono::steady_clock::now();
    auto grid = openvdb::tools::meshToUnsignedDistanceField<openvdb::FloatGrid>(*xform, arrays.points,
                                                                                arrays.triangles, quads, halfWidth);
    MeshToVolumeRun run;
    run.peakBytes = memory.peakBytes();
    run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    run.cpuSeconds = processCpuSeconds() - cpuStart;
    run.activeVoxels = grid->activeVoxelCount();
    run.memoryBytes = grid->memUsage();
    run.leafCount = grid->tree().leafCount();
    return run;
}

std::vector<glm::ivec3> meshToVolumeSurfaceVoxels(const Scene& scene, float voxelSize) {
    initializeOpenVdb();
    detail::MeshArrays arrays = detail::collectMeshArrays(scene);
    std::vector<openvdb::Vec4I> quads;
    auto xform = detail::voxelTransform(voxelSize);
    openvdb::Int32Grid closest(0);
    openvdb::util::NullInterrupter interrupter;
    // The adapter form of meshToVolume takes index-space points.
    std::vector<openvdb::Vec3s> indexPoints(arrays.points.size());
    for (std::size_t i = 0; i < arrays.points.size(); ++i) indexPoints[i] = xform->worldToIndex(arrays.points[i]);
    openvdb::tools::QuadAndTriangleDataAdapter<openvdb::Vec3s, openvdb::Vec3I> mesh(indexPoints, arrays.triangles);
    // A band of 2 voxels holds every centre within sqrt(3)/2 voxel of the surface.
    auto grid = openvdb::tools::meshToVolume<openvdb::FloatGrid>(interrupter, mesh, *xform, 2.0f, 2.0f,
                                                                 openvdb::tools::UNSIGNED_DISTANCE_FIELD, &closest);
    auto index = closest.getConstAccessor();
    std::vector<glm::ivec3> voxels;
    for (auto it = grid->cbeginValueOn(); it; ++it) {
        int tri = index.getValue(it.getCoord());
        if (tri < 0 || std::size_t(tri) >= arrays.triangles.size()) continue;
        const openvdb::Vec3I& t = arrays.triangles[std::size_t(tri)];
        openvdb::Vec3s n = (arrays.points[t[1]] - arrays.points[t[0]]).cross(arrays.points[t[2]] - arrays.points[t[0]]);
        float len = n.length();
        if (!(len > 0.0f)) continue;
        n /= len;
        float reach = 0.5f * voxelSize * (std::abs(n.x()) + std::abs(n.y()) + std::abs(n.z()));
        if (*it <= reach) voxels.emplace_back(it.getCoord().x(), it.getCoord().y(), it.getCoord().z());
    }
    return voxels;
}

}  // namespace voxgi
