// The probe field: one or more probe volumes (cascades) and the atlases they share.
// A volume is a grid of counts.x * counts.y * counts.z probes. Probes are stored toroidally:
// storage = (logical + scroll) mod counts, so a volume that scrolls by whole cells keeps every
// probe's data where it is in the atlas and only the planes that enter are reset.
// Atlas layout: one tile row per horizontal probe plane (y), tiles x + counts.x * z along it;
// cascades are stacked row-wise. Irradiance texels hold E^(1/gamma) (W/m^2 before encoding),
// distance texels (mean distance, mean squared distance) in metres.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "gi/ddgi/ddgi_desc.h"

namespace voxgi {

enum class ProbeState : std::int32_t {
    Active = 0,    // updated every frame
    Sleeping = 1,  // no geometry near: updated every sleepInterval frames
    Off = 2,       // inside geometry: never updated, never sampled
};

struct ProbeVolume {
    glm::ivec3 counts{1};
    glm::vec3 spacing{1.0f};
    glm::vec3 origin{0.0f};  // world position of logical probe (0, 0, 0), before relocation
    glm::ivec3 scroll{0};    // storage = (logical + scroll) mod counts
    int probeBase = 0;       // first probe of this volume in the field's per-probe arrays
    int tileRow = 0;         // first tile row of this volume in the atlases

    int probeCount() const { return counts.x * counts.y * counts.z; }
    glm::ivec3 storageOf(glm::ivec3 logical) const;
    glm::ivec3 logicalOf(glm::ivec3 storage) const;
    int localIndex(glm::ivec3 storage) const { return storage.x + counts.x * (storage.z + counts.z * storage.y); }
    glm::ivec3 storageFromLocal(int local) const;
    glm::ivec2 tile(int local) const;
    glm::vec3 basePosition(glm::ivec3 logical) const { return origin + glm::vec3(logical) * spacing; }
    float cellDiagonal() const { return glm::length(spacing); }
    float minSpacing() const { return glm::min(spacing.x, glm::min(spacing.y, spacing.z)); }
    // Distances stored in the distance atlas are clamped here (just beyond the cage diagonal).
    float maxDistance() const { return 1.5f * cellDiagonal(); }
};

// Texels of square tiles (one per probe), addressed by atlas coordinates (x, y) but stored tile
// by tile: a tile's texels are contiguous, so lookups of one probe stay in a few pages. The GPU
// texture is row-major; toRows / fromRows convert.
struct Atlas {
    int width = 0;
    int height = 0;
    int tile = 1;    // texels per tile side
    int tilesX = 0;  // tiles per atlas row
    std::vector<glm::vec4> texels;

    void resize(int tilesAcross, int tilesDown, int tileSize, glm::vec4 fill);
    std::size_t index(int x, int y) const {
        int tx = x / tile, ty = y / tile;
        return (std::size_t(ty * tilesX + tx) * std::size_t(tile) + std::size_t(y - ty * tile)) * std::size_t(tile) +
               std::size_t(x - tx * tile);
    }
    glm::vec4& at(int x, int y) { return texels[index(x, y)]; }
    const glm::vec4& at(int x, int y) const { return texels[index(x, y)]; }
    // Bilinear lookup at a texel coordinate (texel centres at .5), like GL_LINEAR.
    glm::vec4 bilinear(glm::vec2 coordinate) const;
    // Bilinear lookup inside tile `tileIndex` (in tiles) at a coordinate local to the tile; the
    // 2x2 footprint is clamped into the tile. The lookup the probe sampling uses.
    glm::vec4 bilinearInTile(glm::ivec2 tileIndex, glm::vec2 local) const;
    void toRows(std::vector<glm::vec4>& rows) const;
    void fromRows(const std::vector<glm::vec4>& rows);
};

struct ProbeRecord {
    glm::vec3 offset{0.0f};  // relocation, world units, at most 0.45 cells per axis
    ProbeState state = ProbeState::Active;
    // Blends since the probe's data was last reset (0: none yet). The blend's hysteresis is
    // min(ddgi.hysteresis, n / (n + 1)): a running mean over the first blends, so a new or
    // woken probe converges in about 1 / (1 - hysteresis) frames, then the usual exponential
    // mean (probeHysteresis, probe_blend.h).
    int blends = 0;
    bool fresh() const { return blends == 0; }
};

// Volumes for a desc: a fixed grid fitted to the scene bounds, or camera-centred cascades
// (centred on scrollCentre).
std::vector<ProbeVolume> layoutVolumes(const DdgiDesc& desc, const Bounds& bounds, glm::vec3 eye,
                                       glm::vec3 forward = glm::vec3(0.0f));
// Where a scrolling volume centres: forwardOffset of its extent ahead of the eye along the unit
// `forward` (per axis, so the eye stays inside for offsets up to 0.5), then slid inside the
// scene's bounds (to their centre along an axis the volume spans): probes outside every surface
// light nothing, and a camera outside the scene (the Cornell box seen through its open side)
// would otherwise leave every volume in front of it.
glm::vec3 scrollCentre(const ProbeVolume& volume, glm::vec3 eye, glm::vec3 forward, float forwardOffset,
                       const Bounds& bounds);

class ProbeField {
public:
    ProbeField(const DdgiDesc& desc, std::vector<ProbeVolume> volumes);

    const DdgiDesc& desc() const { return desc_; }
    const std::vector<ProbeVolume>& volumes() const { return volumes_; }
    // The smallest spacing of any volume on any axis (the finest cascade's).
    float smallestSpacing() const;
    int probeCount() const { return int(probes.size()); }
    // Volume index of a global probe index.
    int volumeOf(int probe) const;
    glm::vec3 probePosition(int probe) const;
    glm::ivec2 irradianceTile(int probe) const;  // texel origin of the probe's tile (border included)
    glm::ivec2 distanceTile(int probe) const;
    void resetProbe(int probe);
    // Mean of the decoded irradiance over the probe's interior texels (W/m^2).
    glm::vec3 meanIrradiance(int probe) const;

    // Moves a scrolling volume by whole cells so its centre follows `centre`; resets the probe
    // planes that enter. Returns the shift in cells.
    glm::ivec3 scrollTo(int volume, glm::vec3 centre);
    // The shift scrollTo(volume, centre) would make, without making it.
    glm::ivec3 scrollShift(int volume, glm::vec3 centre) const;

    // Every CPU write to `irradiance` or `distance` (probe resets, the CPU blend) bumps this, so
    // that a GPU copy of the atlases uploads them again only when they changed.
    std::uint64_t atlasVersion() const { return atlasVersion_; }
    void atlasesChanged() { ++atlasVersion_; }

    Atlas irradiance;
    Atlas distance;
    // Occlusion probes: per-light visibility (up to 4 lights, rgba) of the surfaces each probe
    // sees, same layout as `distance`; empty unless desc.directLight is OcclusionProbes.
    Atlas occlusion;
    std::vector<ProbeRecord> probes;

private:
    DdgiDesc desc_;
    std::vector<ProbeVolume> volumes_;
    std::uint64_t atlasVersion_ = 0;
};

}  // namespace voxgi
