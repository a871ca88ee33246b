#include "gi/ddgi/probe_field.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

#include "gi/octahedral/octahedral.h"

namespace voxgi {

namespace {
int positiveMod(int a, int n) { return ((a % n) + n) % n; }
}  // namespace

glm::ivec3 ProbeVolume::storageOf(glm::ivec3 l) const {
    if (scroll == glm::ivec3(0)) return l;
    return {positiveMod(l.x + scroll.x, counts.x), positiveMod(l.y + scroll.y, counts.y),
            positiveMod(l.z + scroll.z, counts.z)};
}

glm::ivec3 ProbeVolume::logicalOf(glm::ivec3 s) const {
    return {positiveMod(s.x - scroll.x, counts.x), positiveMod(s.y - scroll.y, counts.y),
            positiveMod(s.z - scroll.z, counts.z)};
}

glm::ivec3 ProbeVolume::storageFromLocal(int local) const {
    int x = local % counts.x;
    int z = (local / counts.x) % counts.z;
    int y = local / (counts.x * counts.z);
    return {x, y, z};
}

glm::ivec2 ProbeVolume::tile(int local) const {
    glm::ivec3 s = storageFromLocal(local);
    return {s.x + counts.x * s.z, tileRow + s.y};
}

void Atlas::resize(int tilesAcross, int tilesDown, int tileSize, glm::vec4 fill) {
    tile = tileSize;
    tilesX = tilesAcross;
    width = tilesAcross * tileSize;
    height = tilesDown * tileSize;
    texels.assign(std::size_t(width) * std::size_t(height), fill);
}

glm::vec4 Atlas::bilinear(glm::vec2 c) const {
    glm::vec2 p = c - 0.5f;
    glm::vec2 f = glm::floor(p);
    glm::vec2 t = p - f;
    int x0 = std::clamp(int(f.x), 0, width - 1), y0 = std::clamp(int(f.y), 0, height - 1);
    int x1 = std::min(x0 + 1, width - 1), y1 = std::min(y0 + 1, height - 1);
    glm::vec4 a, b, c0, d;
    if ((x0 % tile) + 1 < tile && (y0 % tile) + 1 < tile) {
        // All four texels in one tile (always so inside a bordered tile): one address.
        const glm::vec4* q = &texels[index(x0, y0)];
        a = q[0], b = q[1], c0 = q[tile], d = q[tile + 1];
    } else {
        a = at(x0, y0), b = at(x1, y0), c0 = at(x0, y1), d = at(x1, y1);
    }
    return glm::mix(glm::mix(a, b, t.x), glm::mix(c0, d, t.x), t.y);
}

glm::vec4 Atlas::bilinearInTile(glm::ivec2 tileIndex, glm::vec2 local) const {
    glm::vec2 p = local - 0.5f;
    glm::vec2 f = glm::floor(p);
    glm::vec2 t = p - f;
    int x0 = std::clamp(int(f.x), 0, tile - 2), y0 = std::clamp(int(f.y), 0, tile - 2);
    const glm::vec4* q = &texels[(std::size_t(tileIndex.y * tilesX + tileIndex.x) * std::size_t(tile) + std::size_t(y0)) *
                                     std::size_t(tile) + std::size_t(x0)];
    return glm::mix(glm::mix(q[0], q[1], t.x), glm::mix(q[tile], q[tile + 1], t.x), t.y);
}

namespace {
// Calls copy(row texel, tile texel, count) for each run of one tile's row: the texels are
// tile-major here and row-major in GL, and a run is contiguous in both (every frame on the GL
// path moves whole atlases, so no per-texel index arithmetic).
template <typename Copy>
void forEachTileRow(const Atlas& a, Copy&& copy) {
    tbb::parallel_for(0, a.height, [&](int y) {
        const int ty = y / a.tile, ry = y - ty * a.tile;
        for (int tx = 0; tx < a.tilesX; ++tx)
            copy(std::size_t(y) * std::size_t(a.width) + std::size_t(tx * a.tile),
                 (std::size_t(ty * a.tilesX + tx) * std::size_t(a.tile) + std::size_t(ry)) * std::size_t(a.tile),
                 std::size_t(a.tile));
    });
}
}  // namespace

void Atlas::toRows(std::vector<glm::vec4>& rows) const {
    rows.resize(texels.size());
    forEachTileRow(*this, [&](std::size_t row, std::size_t tiled, std::size_t n) {
        std::copy_n(&texels[tiled], n, &rows[row]);
    });
}

void Atlas::fromRows(const std::vector<glm::vec4>& rows) {
    forEachTileRow(*this, [&](std::size_t row, std::size_t tiled, std::size_t n) {
        std::copy_n(&rows[row], n, &texels[tiled]);
    });
}

glm::vec3 scrollCentre(const ProbeVolume& v, glm::vec3 eye, glm::vec3 forward, float forwardOffset,
                       const Bounds& bounds) {
    const glm::vec3 extent = glm::vec3(v.counts - 1) * v.spacing;
    glm::vec3 centre = eye + forward * (forwardOffset * extent);
    if (!bounds.valid()) return centre;
    for (int k = 0; k < 3; ++k) {
        const float half = 0.5f * extent[k];
        centre[k] = bounds.max[k] - bounds.min[k] <= 2.0f * half
                        ? 0.5f * (bounds.min[k] + bounds.max[k])
                        : std::clamp(centre[k], bounds.min[k] + half, bounds.max[k] - half);
    }
    return centre;
}

std::vector<ProbeVolume> layoutVolumes(const DdgiDesc& desc, const Bounds& bounds, glm::vec3 eye, glm::vec3 forward) {
    glm::vec3 extent = bounds.valid() ? bounds.extent() : glm::vec3(0.0f);
    float longest = std::max(extent.x, std::max(extent.y, extent.z));
    if (!(longest > 0.0f)) extent = glm::vec3(longest = 1.0f);
    // A flat axis (a lone plane) gets a sliver of the longest, relative so that the grid of a
    // scene scaled by any factor is that factor times the same grid (an absolute floor of
    // 0.1 mm had made a 0.1 mm Cornell box's grid about twice its size).
    extent = glm::max(extent, glm::vec3(1e-4f * longest));
    glm::ivec3 counts = desc.probeCounts;
    glm::vec3 spacing = desc.spacing;
    if (counts.x == 0) {
        glm::vec3 cell = spacing.x > 0.0f ? spacing : glm::vec3(longest / float(desc.fitCells));
        // Less a tolerance: the longest axis is fitCells cells exactly, which float rounding of
        // extent / (longest / fitCells) would otherwise make one more.
        counts = glm::clamp(glm::ivec3(glm::ceil(extent / cell - 1e-3f)), glm::ivec3(1), glm::ivec3(64));
    }
    if (spacing.x == 0.0f) spacing = extent / glm::vec3(counts);

    std::vector<ProbeVolume> volumes;
    int tileRow = 0, probeBase = 0;
    for (int c = 0; c < desc.cascades; ++c) {
        ProbeVolume v;
        v.counts = counts;
        v.spacing = spacing * float(1 << c);
        if (desc.scrolls()) {
            // Camera-centred (pushed ahead), snapped to whole cells of this cascade.
            glm::vec3 half = 0.5f * glm::vec3(counts - 1) * v.spacing;
            v.origin = glm::floor((scrollCentre(v, eye, forward, desc.forwardOffset, bounds) - half) / v.spacing + 0.5f) * v.spacing;
        } else {
            // Centred on the bounds; with fitted spacing the probes sit at cell centres, so
            // none lies on the bounding walls.
            glm::vec3 centre = bounds.valid() ? bounds.center() : glm::vec3(0.0f);
            v.origin = centre - 0.5f * glm::vec3(counts - 1) * v.spacing;
        }
        v.tileRow = tileRow;
        v.probeBase = probeBase;
        tileRow += counts.y;
        probeBase += v.probeCount();
        volumes.push_back(v);
    }
    return volumes;
}

ProbeField::ProbeField(const DdgiDesc& desc, std::vector<ProbeVolume> volumes)
    : desc_(desc), volumes_(std::move(volumes)) {
    int tilesX = 1, tilesY = 0, total = 0;
    for (const ProbeVolume& v : volumes_) {
        tilesX = std::max(tilesX, v.counts.x * v.counts.z);
        tilesY += v.counts.y;
        total += v.probeCount();
    }
    irradiance.resize(tilesX, tilesY, oct::tileSize(desc_.irradianceTexels), glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    distance.resize(tilesX, tilesY, oct::tileSize(desc_.distanceTexels), glm::vec4(0.0f));
    if (desc_.directLight == DdgiDirectLight::OcclusionProbes)
        occlusion.resize(tilesX, tilesY, oct::tileSize(desc_.distanceTexels), glm::vec4(1.0f));
    probes.assign(std::size_t(total), ProbeRecord{});
    for (int p = 0; p < total; ++p) resetProbe(p);
}

int ProbeField::volumeOf(int probe) const {
    for (int v = int(volumes_.size()) - 1; v >= 0; --v)
        if (probe >= volumes_[std::size_t(v)].probeBase) return v;
    return 0;
}

float ProbeField::smallestSpacing() const {
    float spacing = volumes_.front().minSpacing();
    for (const ProbeVolume& v : volumes_) spacing = std::min(spacing, v.minSpacing());
    return spacing;
}

glm::vec3 ProbeField::probePosition(int probe) const {
    const ProbeVolume& v = volumes_[std::size_t(volumeOf(probe))];
    glm::ivec3 logical = v.logicalOf(v.storageFromLocal(probe - v.probeBase));
    return v.basePosition(logical) + probes[std::size_t(probe)].offset;
}

glm::ivec2 ProbeField::irradianceTile(int probe) const {
    const ProbeVolume& v = volumes_[std::size_t(volumeOf(probe))];
    return v.tile(probe - v.probeBase) * oct::tileSize(desc_.irradianceTexels);
}

glm::ivec2 ProbeField::distanceTile(int probe) const {
    const ProbeVolume& v = volumes_[std::size_t(volumeOf(probe))];
    return v.tile(probe - v.probeBase) * oct::tileSize(desc_.distanceTexels);
}

void ProbeField::resetProbe(int probe) {
    // No light yet, and every direction open up to the clamp distance (no visibility cut).
    atlasesChanged();
    const ProbeVolume& v = volumes_[std::size_t(volumeOf(probe))];
    float far = v.maxDistance();
    glm::ivec2 it = irradianceTile(probe), dt = distanceTile(probe);
    int ni = oct::tileSize(desc_.irradianceTexels), nd = oct::tileSize(desc_.distanceTexels);
    for (int y = 0; y < ni; ++y)
        for (int x = 0; x < ni; ++x) irradiance.at(it.x + x, it.y + y) = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
    for (int y = 0; y < nd; ++y)
        for (int x = 0; x < nd; ++x) {
            distance.at(dt.x + x, dt.y + y) = glm::vec4(far, far * far, 0.0f, 0.0f);
            if (!occlusion.texels.empty()) occlusion.at(dt.x + x, dt.y + y) = glm::vec4(1.0f);
        }
    probes[std::size_t(probe)] = ProbeRecord{};
}

glm::vec3 ProbeField::meanIrradiance(int probe) const {
    glm::ivec2 t = irradianceTile(probe);
    int n = desc_.irradianceTexels;
    glm::vec3 sum(0.0f);
    for (int y = 1; y <= n; ++y)
        for (int x = 1; x <= n; ++x) sum += glm::pow(glm::vec3(irradiance.at(t.x + x, t.y + y)), glm::vec3(desc_.irradianceGamma));
    return sum / float(n * n);
}

glm::ivec3 ProbeField::scrollShift(int index, glm::vec3 target) const {
    const ProbeVolume& v = volumes_[std::size_t(index)];
    glm::vec3 centre = v.origin + 0.5f * glm::vec3(v.counts - 1) * v.spacing;
    return glm::ivec3(glm::floor((target - centre) / v.spacing + 0.5f));
}

glm::ivec3 ProbeField::scrollTo(int index, glm::vec3 target) {
    ProbeVolume& v = volumes_[std::size_t(index)];
    const glm::ivec3 shift = scrollShift(index, target);
    if (shift == glm::ivec3(0)) return shift;
    v.origin += glm::vec3(shift) * v.spacing;
    v.scroll += shift;
    v.scroll = glm::ivec3(positiveMod(v.scroll.x, v.counts.x), positiveMod(v.scroll.y, v.counts.y),
                          positiveMod(v.scroll.z, v.counts.z));
    // A logical plane is new when it lies beyond the old extent on the side the volume moved to.
    for (int local = 0; local < v.probeCount(); ++local) {
        glm::ivec3 l = v.logicalOf(v.storageFromLocal(local));
        bool entered = false;
        for (int a = 0; a < 3; ++a) {
            if (shift[a] > 0) entered |= l[a] >= v.counts[a] - shift[a];
            if (shift[a] < 0) entered |= l[a] < -shift[a];
        }
        if (entered) resetProbe(v.probeBase + local);
    }
    return shift;
}

}  // namespace voxgi
