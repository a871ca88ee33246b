#include "gi/lpv/tap_masks.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include <tbb/parallel_for.h>

#include "gi/raytrace/ray_tracer.h"
#include "scenes/scene.h"

namespace voxgi {

namespace {
constexpr int kClasses = 6;
constexpr int kKeptPoints = 8;
// A triangle is sampled on a lattice of at most this many steps per edge (a few huge floor
// triangles: points closer than that add nothing a cell's four kept points would not have).
constexpr int kMaxSteps = 512;

struct KeptPoints {
    int seen = 0;  // points offered
    int count = 0;
    glm::vec3 points[kKeptPoints];
    glm::vec3 normals[kKeptPoints];
};

std::uint32_t mix32(std::uint32_t x) {
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    return x ^ (x >> 16);
}
}  // namespace

int tapMaskClass(glm::vec3 n) {
    const glm::vec3 a = glm::abs(n);
    const int axis = a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
    return 2 * axis + (n[axis] < 0.0f ? 1 : 0);
}

std::vector<std::uint32_t> traceTapMasks(const Scene& scene, const RayTracer& tracer, const CascadeGrid& grid,
                                         const BrickMap& bricks) {
    const float h = grid.cellSize;
    const std::size_t cells = bricks.slots() * std::size_t(shading::kBrickCells);
    std::vector<std::uint32_t> masks(cells * kClasses, kAllTapBits);
    // Up to kKeptPoints points per stored cell and side, kept as reservoir samples (a hash of the
    // offer's number decides), so a cell's points spread over its surfaces whatever their order.
    std::unordered_map<std::size_t, KeptPoints> kept;
    auto offer = [&](glm::vec3 x, glm::vec3 n) {
        const glm::ivec3 local = grid.cellOf(x);
        const int slot = bricks.slotOf(local);
        if (slot < 0) return;
        const std::size_t key = BrickMap::brickCell(slot, local) * kClasses + std::size_t(tapMaskClass(n));
        KeptPoints& k = kept[key];
        int at = k.count < kKeptPoints ? k.count++ : int(mix32(std::uint32_t(key * 2654435761u) ^ std::uint32_t(k.seen)) %
                                                          std::uint32_t(k.seen + 1));
        ++k.seen;
        if (at < kKeptPoints) {
            k.points[at] = x;
            k.normals[at] = n;
        }
    };
    for (const Mesh& mesh : scene.meshes) {
        if (mesh.isQuadLightGeometry()) continue;
        for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
            const glm::vec3 a = mesh.positions[mesh.indices[3 * t]], b = mesh.positions[mesh.indices[3 * t + 1]],
                            c = mesh.positions[mesh.indices[3 * t + 2]];
            const glm::vec3 cr = glm::cross(b - a, c - a);
            const float len = glm::length(cr);
            if (!(len > 0.0f)) continue;
            const glm::vec3 n = cr / len;
            const float edge = std::max({glm::length(b - a), glm::length(c - b), glm::length(a - c)});
            const int m = std::clamp(int(std::ceil(edge / (0.5f * h))), 1, kMaxSteps);
            // The centroids of the m^2 triangles of the lattice that cuts each edge into m.
            for (int i = 0; i < m; ++i)
                for (int j = 0; i + j < m; ++j)
                    for (int up = 0; up < (i + j + 1 < m ? 2 : 1); ++up) {
                        const float u = (float(i) + (up ? 2.0f : 1.0f) / 3.0f) / float(m);
                        const float v = (float(j) + (up ? 2.0f : 1.0f) / 3.0f) / float(m);
                        const glm::vec3 x = a + u * (b - a) + v * (c - a);
                        offer(x, n);
                        offer(x, -n);
                    }
        }
    }
    std::vector<std::pair<std::size_t, const KeptPoints*>> entries;
    entries.reserve(kept.size());
    for (const auto& [key, k] : kept) entries.push_back({key, &k});
    const float offset = surfaceRayOffset(scene);
    tbb::parallel_for(std::size_t(0), entries.size(), [&](std::size_t e) {
        const auto [key, k] = entries[e];
        const std::size_t cell = key / kClasses;
        const int slot = int(cell / std::size_t(shading::kBrickCells));
        const glm::ivec3 home = bricks.slotOrigins()[std::size_t(slot)] +
                                glm::ivec3(int(cell % 8), int(cell / 8 % 8), int(cell / 64 % 8));
        std::uint32_t mask = 0;
        for (int dz = -1; dz <= 1; ++dz)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const glm::ivec3 d(dx, dy, dz);
                    const glm::vec3 centre = grid.cellCenter(home + d);
                    int seen = 0;
                    for (int p = 0; p < k->count; ++p) {
                        const glm::vec3 x = k->points[p], n = k->normals[p];
                        const glm::vec3 o = x + n * offset;
                        const glm::vec3 to = centre - o;
                        const float dist = glm::length(to);
                        const bool behind = glm::dot(centre - x, n) <= 0.0f;
                        if (behind || !(dist > 0.0f) || !tracer.occluded(o, to / dist, 0.0f, dist)) ++seen;
                    }
                    if (seen > 0) mask |= 1u << tapMaskBit(d);
                }
        masks[key] = mask;
    });
    return masks;
}

}  // namespace voxgi
