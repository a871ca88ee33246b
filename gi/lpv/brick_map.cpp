#include "gi/lpv/brick_map.h"

#include <algorithm>

namespace voxgi {

BrickMap::BrickMap(int resolution) : resolution_(resolution), side_(shading::bricksPerSide(resolution)) {
    table_.assign(std::size_t(side_) * std::size_t(side_) * std::size_t(side_), -1);
}

template <typename F>
void BrickMap::forEachBrickAround(glm::ivec3 cell, int reach, F f) const {
    const glm::ivec3 lo = glm::max(cell - reach, glm::ivec3(0)), hi = glm::min(cell + reach, glm::ivec3(resolution_ - 1));
    if (glm::any(glm::greaterThan(lo, hi))) return;
    const glm::ivec3 b0 = lo / shading::kBrickSide, b1 = hi / shading::kBrickSide;
    for (int z = b0.z; z <= b1.z; ++z)
        for (int y = b0.y; y <= b1.y; ++y)
            for (int x = b0.x; x <= b1.x; ++x) f(std::size_t((z * side_ + y) * side_ + x));
}

void BrickMap::allocate(std::size_t brick) {
    if (table_[brick] >= 0) return;
    table_[brick] = int(origins_.size());
    const std::size_t side = std::size_t(side_);
    origins_.push_back(glm::ivec3(int(brick % side), int(brick / side % side), int(brick / (side * side))) *
                       shading::kBrickSide);
}

void BrickMap::allocateAround(glm::ivec3 cell, int reach) {
    forEachBrickAround(cell, reach, [&](std::size_t brick) { allocate(brick); });
}

void BrickMap::allocateAround(const std::vector<glm::ivec3>& cells, int reach) {
    std::vector<char> wanted(table_.size(), 0);
    for (const glm::ivec3& cell : cells) forEachBrickAround(cell, reach, [&](std::size_t brick) { wanted[brick] = 1; });
    for (std::size_t brick = 0; brick < table_.size(); ++brick)
        if (wanted[brick]) allocate(brick);
}

void BrickMap::allocateAll() {
    for (std::size_t brick = 0; brick < table_.size(); ++brick) allocate(brick);
}

}  // namespace voxgi
