// Which 8^3 bricks of a cascade hold light (shaders/shared/light_bricks.h): allocated where the
// voxelized surfaces are, dilated by the cells a receiver reads around them, so memory follows
// the occupancy instead of the volume. Bricks are only added while the cascade stays placed.
#pragma once

#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "shaders/shared/light_bricks.h"

namespace voxgi {

class BrickMap {
public:
    BrickMap() = default;
    explicit BrickMap(int resolution);

    // Allocates every brick holding a cell of the grid within `reach` cells (per axis) of `cell`.
    void allocateAround(glm::ivec3 cell, int reach);
    // The same around many cells, new slots in the table's order (x fastest): a row of bricks
    // along x is a run of slots, so a sweep along x reads memory at a constant stride.
    void allocateAround(const std::vector<glm::ivec3>& cells, int reach);
    void allocateAll();

    // Slot of the brick holding a cell, -1 where none is allocated (or outside the grid).
    int slotOf(glm::ivec3 cell) const {
        const bool inside = glm::all(glm::greaterThanEqual(cell, glm::ivec3(0))) &&
                            glm::all(glm::lessThan(cell, glm::ivec3(resolution_)));
        if (!inside) return -1;
        return slotOfInside(cell);
    }
    // The same for a cell known to be inside the grid.
    int slotOfInside(glm::ivec3 cell) const { return table_[std::size_t(shading::brickTableIndex(cell, side_))]; }
    // A cell's index among the slots' cells ([slot][kBrickCells], slotOf(cell) >= 0): in the
    // surface indices, and in each face of an irradiance cube (faceStride values per face).
    static std::size_t brickCell(int slot, glm::ivec3 cell) { return std::size_t(shading::brickCell(slot, cell)); }
    std::size_t faceStride() const { return std::size_t(shading::brickValue(int(slots()), 0, 1)); }
    std::size_t slots() const { return origins_.size(); }
    // Values of an irradiance cube over the slots (six faces of each slot's cells).
    static constexpr std::size_t kSlotValues = 6 * std::size_t(shading::kBrickCells);
    std::size_t valueCount() const { return slots() * kSlotValues; }
    int tableSide() const { return side_; }
    std::size_t tableSize() const { return table_.size(); }

    // For the GPU's and the dump's copies: the table (per brick, its slot or -1) and each slot's
    // first cell (the OpenVDB leaf's origin).
    const std::vector<int>& table() const { return table_; }
    const std::vector<glm::ivec3>& slotOrigins() const { return origins_; }

private:
    // f(table index) for every brick holding a cell of the grid within `reach` of `cell`.
    template <typename F>
    void forEachBrickAround(glm::ivec3 cell, int reach, F f) const;
    void allocate(std::size_t brick);  // by table index; a slot unless it has one

    int resolution_ = 0;
    int side_ = 0;
    std::vector<int> table_;
    std::vector<glm::ivec3> origins_;
};

}  // namespace voxgi
