#include "gi/lpv/injection.h"

#include <algorithm>
#include <array>
#include <utility>
#include <cmath>

#include "gi/sh/sh.h"
#include "shaders/shared/constants.h"

namespace voxgi {

namespace {
glm::vec4 toVec4(const sh::Sh4& s) { return {s.c[0], s.c[1], s.c[2], s.c[3]}; }
}  // namespace

glm::vec4 fullBlocker(glm::vec3 n) { return toVec4(sh::cosineLobe(n)) * (4.0f / 3.0f); }

namespace {
// Adds each surfel's VPL to the volumes `split` names for it: (volume, weight) pairs.
template <typename Split>
double addVpls(const SurfelSource& source, const InjectionOffsets& offsets, const CascadeGrid& grid, Split split) {
    const float h = grid.cellSize;
    double total = 0.0;
    for (const Surfel& s : source.surfels) {
        if (s.flux == glm::vec3(0.0f)) continue;
        glm::vec3 p = s.position + s.normal * (offsets.normalCells * h) + s.toLight * (offsets.lightCells * h);
        glm::ivec3 cell = grid.cellOf(p);
        if (!grid.contains(cell)) continue;
        glm::vec4 lobe = toVec4(sh::cosineLobe(s.normal)) / shading::kPi;  // unit-flux cosine lobe
        std::size_t i = grid.index(cell);
        float weights = 0.0f;
        for (const auto& [volume, weight] : split(p)) {
            if (weight <= 0.0f) continue;
            volume->r[i] += lobe * (s.flux.r * weight);
            volume->g[i] += lobe * (s.flux.g * weight);
            volume->b[i] += lobe * (s.flux.b * weight);
            weights += weight;
        }
        total += double(weights) * (double(s.flux.r) + double(s.flux.g) + double(s.flux.b));
    }
    return total;
}
using Part = std::pair<LightVolume*, float>;
}  // namespace

double injectLight(const SurfelSource& source, const InjectionOffsets& offsets, LightVolume& volume) {
    return addVpls(source, offsets, volume.grid, [&](glm::vec3) { return std::array<Part, 1>{Part{&volume, 1.0f}}; });
}

double injectLight(const SurfelSource& source, const InjectionOffsets& offsets,
                   const std::vector<CascadePlacement>& cascades, std::size_t level, LightVolume& ring,
                   LightVolume& inner) {
    return addVpls(source, offsets, ring.grid, [&](glm::vec3 p) {
        const SourceShares share = sourceShares(cascades, level, p);
        return std::array<Part, 2>{Part{&ring, share.ring}, Part{&inner, share.inner}};
    });
}

void injectBlockers(const SurfelSource& source, BlockerVolume& scratch, BlockerVolume& volume) {
    const CascadeGrid& grid = volume.grid;
    const float h = grid.cellSize;
    const int corners = volume.cornerCount();
    std::vector<std::size_t> touched;
    for (const Surfel& s : source.surfels) {
        // Geometry samples sit at the light volume's cell corners: the nearest corner owns it.
        glm::ivec3 c = glm::ivec3(glm::floor(s.position / h + 0.5f)) - grid.origin;
        if (glm::any(glm::lessThan(c, glm::ivec3(0))) || glm::any(glm::greaterThanEqual(c, glm::ivec3(corners))))
            continue;
        std::size_t i = volume.cornerIndex(c);
        if (scratch.blocker[i] == glm::vec4(0.0f)) touched.push_back(i);
        scratch.blocker[i] += fullBlocker(s.normal) * (s.area / (h * h));
        scratch.albedo[i] = glm::max(scratch.albedo[i], s.albedo);
    }
    for (std::size_t i : touched) {
        volume.blocker[i] = mergeBlockers(volume.blocker[i], scratch.blocker[i]);
        volume.albedo[i] = glm::max(volume.albedo[i], scratch.albedo[i]);
        scratch.blocker[i] = glm::vec4(0.0f);
        scratch.albedo[i] = glm::vec3(0.0f);
    }
}

}  // namespace voxgi
