// Reading any .vdb file for people: per-grid summaries (like vdb_print), value histograms and
// coloured slices. Works on files from any tool, not only voxgi's.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "volumes/geometry_volume.h"

namespace voxgi {

struct VdbGridInfo {
    std::string name;
    std::string valueType;   // "float", "vec3s", "bool", ...
    std::string gridClass;   // "level set", "fog volume", "unknown", ...
    glm::dvec3 voxelSize{0.0};
    std::uint64_t activeVoxels = 0;
    IndexBox indexBox;                 // active voxels, inclusive
    glm::dvec3 worldMin{0.0}, worldMax{0.0};  // outer faces of the active voxels
    std::uint64_t memoryBytes = 0;
    std::vector<std::pair<std::string, std::string>> metadata;  // name, value as text
};

struct VdbFileInfo {
    std::vector<std::pair<std::string, std::string>> metadata;
    std::vector<VdbGridInfo> grids;
};

// Throws InputError ("<path>: ...") for absent, unreadable or corrupt files.
VdbFileInfo inspectVdbFile(const std::string& path);

struct VdbHistogram {
    std::string grid;
    std::string quantity;   // "value", "length" (vectors) or "active" (bool/mask)
    double min = 0.0, max = 0.0;
    std::vector<std::uint64_t> counts;  // equal-width bins over [min, max] (one bin for bool)
};
std::vector<VdbHistogram> vdbHistograms(const std::string& path, int bins);

struct VdbSlice {
    std::string grid;
    int width = 0, height = 0;          // pixels = voxels, top row = largest second axis
    std::vector<std::uint8_t> rgb;
    int indexPlane = 0;                 // the index coordinate sliced
    double valueMin = 0.0, valueMax = 0.0;  // colour ramp range for scalar grids
};
// A slice through the voxel layer holding world coordinate `world` on `axis` (0 x, 1 y, 2 z),
// over the grid's active bounding box. `grid` empty: albedo if present, else the first grid.
// Albedo is shown in sRGB, other vectors as 0.5 + 0.5 v, scalars on a blue-red ramp, bool/mask
// as white; inactive voxels dark.
VdbSlice sliceVdbFile(const std::string& path, const std::string& grid, int axis, double world);

}  // namespace voxgi
