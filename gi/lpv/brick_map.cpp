#include "gi/lpv/brick_map.h"

#include <algorithm>

namespace voxgi {

BrickMap::BrickMap(int resolution) : resolution_(resolution), side_(shading::bricksPerSide(resolution)) {
    table_.assign(std::size_t(side_) * std::size_t(side_) * std::size_t(side_), -1);
}

void BrickMap::allocateAround(glm::ivec3 cell, int reach) {
    allocateCells(glm::max(cell - reach, glm::ivec3(0)), glm::min(cell + reach, glm::ivec3(resolution_ - 1)));
}

void BrickMap::allocateAround(const std::vector<glm::ivec3>& cells, int reach) {
    std::vector<char> wanted(table_.size(), 0);
    for (const glm::ivec3& cell : cells) {
        const glm::ivec3 lo = glm::max(cell - reach, glm::ivec3(0)) / shading::kBrickSide,
                         hi = glm::min(cell + reach, glm::ivec3(resolution_ - 1)) / shading::kBrickSide;
        for (int z = lo.z; z <= hi.z; ++z)
            for (int y = lo.y; y <= hi.y; ++y)
                for (int x = lo.x; x <= hi.x; ++x) wanted[std::size_t((z * side_ + y) * side_ + x)] = 1;
    }
    for (std::size_t i = 0; i < table_.size(); ++i)
        if (wanted[i] && table_[i] < 0) {
            table_[i] = int(origins_.size());
            const int x = int(i % std::size_t(side_)), y = int(i / std::size_t(side_) % std::size_t(side_)),
                      z = int(i / (std::size_t(side_) * std::size_t(side_)));
            origins_.push_back(glm::ivec3(x, y, z) * shading::kBrickSide);
        }
}

void BrickMap::allocateCells(glm::ivec3 lo, glm::ivec3 hi) {
    if (glm::any(glm::greaterThan(lo, hi))) return;
    const glm::ivec3 b0 = lo / shading::kBrickSide, b1 = hi / shading::kBrickSide;
    for (int z = b0.z; z <= b1.z; ++z)
        for (int y = b0.y; y <= b1.y; ++y)
            for (int x = b0.x; x <= b1.x; ++x) {
                int& slot = table_[std::size_t((z * side_ + y) * side_ + x)];
                if (slot >= 0) continue;
                slot = int(origins_.size());
                origins_.push_back(glm::ivec3(x, y, z) * shading::kBrickSide);
            }
}

void BrickMap::allocateAll() { allocateCells(glm::ivec3(0), glm::ivec3(resolution_ - 1)); }

}  // namespace voxgi
