// lpv.tap_visibility=cells: which of the 27 cells around a surface cell its surfaces see, per side
// a receiver there may face, traced once per cascade placement instead of a ray per pixel and
// tap (lpv.tap_visibility=rays). The apply pass reads a receiver's mask from the cell its surface
// point lies in and the axis its normal is closest to (shaders/lpv/apply_ordinates.frag).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "gi/lpv/brick_map.h"
#include "gi/lpv/light_volume.h"

namespace voxgi {

class RayTracer;
struct Scene;

// The side of a surface a normal faces: 2 axis + (1 where it points down the axis), the axis the
// normal is closest to (x before y before z on ties). The GLSL twin is in apply_ordinates.frag.
int tapMaskClass(glm::vec3 n);
// Bit of the neighbour at offset d (each component -1, 0 or 1) in a mask.
inline int tapMaskBit(glm::ivec3 d) { return (d.x + 1) + 3 * (d.y + 1) + 9 * (d.z + 1); }
constexpr std::uint32_t kAllTapBits = (1u << 27) - 1u;

// A receiver's mask is that of the half-cell its surface point lies in (subcell: x + 2 y + 4 z,
// each 1 in the upper half of the cell along that axis) and of its class.
constexpr int kTapSubcells = 8;
constexpr int kTapMasksPerCell = kTapSubcells * 6;

struct TapMasks {
    // Per stored cell of the bricks (BrickMap::brickCell): where its kTapMasksPerCell masks start
    // in `masks`, over kTapMasksPerCell; -1 for a cell without surfaces (it sees everything).
    std::vector<std::int32_t> cells;
    // Per surface cell, subcell and class: bit tapMaskBit(d) set where the subcell's surfaces
    // facing that side see the centre of the cell at offset d from theirs, or where that centre
    // lies behind them (kAllTapBits where it has no such surfaces).
    std::vector<std::uint32_t> masks;
};

// Points sampled on the scene's triangles, at most h / 4 apart (both sides of each), up to four
// kept per subcell and side; a neighbour counts as seen when any of them sees it. `tracer`
// traces `scene`'s triangles.
TapMasks traceTapMasks(const Scene& scene, const RayTracer& tracer, const CascadeGrid& grid, const BrickMap& bricks);

}  // namespace voxgi
