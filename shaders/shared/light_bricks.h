// The sparse light volumes' layout (lpv.transport=ordinates), one definition for C++
// (gi/lpv/brick_map.h) and GLSL (shaders/lpv/): a cascade's cells are grouped into 8^3 bricks
// from its first cell on, as OpenVDB's leaf nodes group the voxels of an index space whose origin
// is that cell, so the dump writes each brick as one leaf. Within a brick x runs fastest, as in
// the dense volumes: the sweeps along y and z run along x (OpenVDB's leaves run z fastest; the
// dump reorders).
//
// A brick table per cascade (ceil(N / 8)^3 ints, x fastest: the brick's slot, -1 where none is
// allocated) and a pool of slots. A volume's irradiance cube over its S slots is six faces, each
// S x 512 values (brickValue): a sweep adds to three faces, each along contiguous cells, as the
// dense volumes had them. Cells are the cascade's own (local).
#ifndef VOXGI_SHARED_LIGHT_BRICKS_H
#define VOXGI_SHARED_LIGHT_BRICKS_H

#include "language.h"

#ifdef __cplusplus
namespace voxgi::shading {
using namespace glm;
#endif

constexpr int kBrickSide = 8;
constexpr int kBrickCells = 512;

// A cell's offset in its brick (x fastest).
inline int brickCellOffset(ivec3 c) { return (c.x & 7) | ((c.y & 7) << 3) | ((c.z & 7) << 6); }

// A cell's place among its volume's slots' cells: its brick's slot and its offset there.
inline int brickCell(int slot, ivec3 c) { return slot * kBrickCells + brickCellOffset(c); }

// Face f of a cell (brickCell) of a volume with `slots` slots, from the volume's first value.
inline int brickValue(int slots, int cell, int face) { return face * slots * kBrickCells + cell; }

// Bricks along each axis of an n^3 grid.
inline int bricksPerSide(int n) { return (n + kBrickSide - 1) / kBrickSide; }

// Index in the brick table of the brick holding cell c (inside the grid).
inline int brickTableIndex(ivec3 c, int side) { return ((c.z >> 3) * side + (c.y >> 3)) * side + (c.x >> 3); }

#ifdef __cplusplus
}  // namespace voxgi::shading
#endif

#endif
