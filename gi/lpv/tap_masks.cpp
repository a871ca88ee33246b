#include "gi/lpv/tap_masks.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

#include "gi/raytrace/ray_tracer.h"
#include "scenes/memory_limit.h"
#include "scenes/scene.h"

namespace voxgi {

namespace {
constexpr int kClasses = 6;
constexpr int kKeptPoints = 4;
// A triangle is sampled on a lattice of at most this many steps per edge, to bound the work a
// huge triangle makes; on one more than 128 cells long some half cells get no point, and keep
// every tap there.
constexpr int kMaxSteps = 512;

// A surface cell holds kTapMasksPerCell of these while its points are sampled.
struct KeptPoints {
    std::uint32_t seen = 0;  // points offered
    glm::vec3 points[kKeptPoints];
    std::int8_t normals[kKeptPoints][3];  // unit normals, in 127ths
    int count() const { return int(std::min<std::uint32_t>(seen, kKeptPoints)); }
    glm::vec3 normal(int i) const { return glm::normalize(glm::vec3(normals[i][0], normals[i][1], normals[i][2])); }
};
static_assert(sizeof(KeptPoints) == 64, "KeptPoints: what the memory check counts");

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

TapMasks traceTapMasks(const Scene& scene, const RayTracer& tracer, const CascadeGrid& grid, const BrickMap& bricks) {
    const float h = grid.cellSize;
    TapMasks out;
    out.cells.assign(bricks.slots() * std::size_t(shading::kBrickCells), -1);
    // Up to kKeptPoints points per stored cell, subcell and side, kept as reservoir samples (a
    // hash of the offer's number decides), so they spread over its surfaces whatever their order:
    // kTapMasksPerCell of them for each cell a surface touches (the cell's TapMasks::cells entry
    // numbers them while sampling), kept[first * kTapMasksPerCell + subcell * 6 + class].
    std::vector<KeptPoints> kept;
    auto offer = [&](glm::vec3 x, glm::vec3 n) {
        const glm::vec3 at = x / h - glm::vec3(grid.origin);
        const glm::ivec3 local = glm::ivec3(glm::floor(at));
        const int slot = bricks.slotOf(local);
        if (slot < 0) return;
        const glm::ivec3 half = glm::clamp(glm::ivec3(glm::floor((at - glm::vec3(local)) * 2.0f)), glm::ivec3(0), glm::ivec3(1));
        const std::size_t sub = std::size_t(half.x + 2 * half.y + 4 * half.z);
        std::int32_t& first = out.cells[BrickMap::brickCell(slot, local)];
        if (first < 0) {
            if (kept.size() == kept.capacity()) {
                const std::size_t grown = std::max<std::size_t>(2 * kept.capacity(), 1024 * kTapMasksPerCell);
                requireMemory(double(grown) * sizeof(KeptPoints), "lpv.tap_visibility=cells: points of the surface cells");
                kept.reserve(grown);
            }
            first = std::int32_t(kept.size() / kTapMasksPerCell);
            kept.resize(kept.size() + kTapMasksPerCell);
        }
        const std::size_t key = std::size_t(first) * kTapMasksPerCell + sub * kClasses + std::size_t(tapMaskClass(n));
        KeptPoints& k = kept[key];
        const std::uint32_t put = k.seen < kKeptPoints ? k.seen : mix32(std::uint32_t(key * 2654435761u) ^ k.seen) % (k.seen + 1);
        ++k.seen;
        if (put < kKeptPoints) {
            k.points[put] = x;
            for (int a = 0; a < 3; ++a) k.normals[put][a] = std::int8_t(std::lround(127.0f * n[a]));
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
            const int m = std::clamp(int(std::ceil(edge / (0.25f * h))), 1, kMaxSteps);
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
    // Each surface cell's stored-cell index, for its position.
    std::vector<std::size_t> surfaceCells(kept.size() / kTapMasksPerCell);
    for (std::size_t cell = 0; cell < out.cells.size(); ++cell)
        if (out.cells[cell] >= 0) surfaceCells[std::size_t(out.cells[cell])] = cell;
    out.masks.assign(kept.size(), kAllTapBits);
    const float offset = surfaceRayOffset(scene);
    tbb::parallel_for(std::size_t(0), kept.size(), [&](std::size_t key) {
        const KeptPoints* k = &kept[key];
        if (k->seen == 0) return;
        const std::size_t cell = surfaceCells[key / kTapMasksPerCell];
        const int slot = int(cell / std::size_t(shading::kBrickCells));
        const glm::ivec3 home = bricks.slotOrigins()[std::size_t(slot)] +
                                glm::ivec3(int(cell % 8), int(cell / 8 % 8), int(cell / 64 % 8));
        std::uint32_t mask = 0;
        for (int dz = -1; dz <= 1; ++dz)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const glm::ivec3 d(dx, dy, dz);
                    const glm::vec3 centre = grid.cellCenter(home + d);
                    bool seen = false;
                    for (int p = 0; p < k->count() && !seen; ++p) {
                        const glm::vec3 x = k->points[p], n = k->normal(p);
                        const glm::vec3 o = x + n * offset;
                        const glm::vec3 to = centre - o;
                        const float dist = glm::length(to);
                        seen = glm::dot(centre - x, n) <= 0.0f || !(dist > 0.0f) || !tracer.occluded(o, to / dist, 0.0f, dist);
                    }
                    if (seen) mask |= 1u << tapMaskBit(d);
                }
        out.masks[key] = mask;
    });
    return out;
}

}  // namespace voxgi
