// .vdb files and the cache. Grids are grouped back into levels by name; anything missing or of
// the wrong type is reported as an InputError naming the file.
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "scenes/errors.h"
#include "volumes/detail/geometry_grids.h"
#include "volumes/detail/vdb_file.h"
#include "volumes/geometry_volume.h"
#include "volumes/openvdb_file.h"
#include "volumes/openvdb_setup.h"

namespace voxgi {

namespace {

// FNV-1a, 64 bit: stable across runs and machines, fast enough for millions of vertices.
struct Hasher {
    std::uint64_t h = 1469598103934665603ull;
    void bytes(const void* data, std::size_t n) {
        const auto* p = static_cast<const unsigned char*>(data);
        for (std::size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 1099511628211ull;
    }
    template <typename T> void vec(const std::vector<T>& v) {
        std::uint64_t n = v.size();
        bytes(&n, sizeof n);
        if (n) bytes(v.data(), n * sizeof(T));
    }
    template <typename T> void pod(const T& v) { bytes(&v, sizeof v); }
    void str(const std::string& s) { vec(std::vector<char>(s.begin(), s.end())); }
};

// Bumped whenever the voxelizer's output for the same input changes, invalidating caches.
// 2: the albedo grid holds the diffuse albedo (metallic and specular taken out).
// 3: pieces clipped row, column, then voxel (the same areas to float rounding).
// 4: the projected coverage per axis (projected_coverage grids).
constexpr int kFormatRevision = 4;

}  // namespace

std::string geometryHash(const Scene& scene, const VoxelizeSettings& settings) {
    Hasher hs;
    hs.pod(kFormatRevision);
    for (const Mesh& m : scene.meshes) {
        hs.vec(m.positions);
        hs.vec(m.uvs);
        hs.vec(m.indices);
        hs.vec(m.materialIds);
    }
    for (const Material& m : scene.materials) {
        hs.pod(m.albedo);
        hs.pod(m.metallic);
        hs.pod(m.specular);
        hs.pod(m.albedoTexture);
    }
    for (const Texture& t : scene.textures) {
        hs.str(t.path);
        hs.pod(t.width);
        hs.pod(t.height);
        hs.pod(t.averageLinear);
    }
    hs.pod(settings.voxelSize);
    hs.pod(settings.levels);
    hs.pod(settings.sdf);
    hs.pod(settings.sdfHalfWidth);
    hs.pod(settings.blockerFit);
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(hs.h));
    return hex;
}

void writeGeometryVolume(const std::string& path, const SparseGeometryVolume& volume) {
    initializeOpenVdb();
    const detail::GeometryGrids& g = volume.grids();
    openvdb::MetaMap meta;
    meta.insertMeta("voxgi_version", openvdb::StringMetadata(VOXGI_VERSION));
    meta.insertMeta("voxgi_source_hash", openvdb::StringMetadata(g.sourceHash));
    meta.insertMeta("voxgi_levels", openvdb::Int32Metadata(int(g.levels.size())));
    meta.insertMeta("voxgi_blocker_fit", openvdb::StringMetadata(blockerFitName(g.blockerFit)));
    writeVdbFile(path, detail::expandGrids(g), meta);
}

namespace {

template <typename GridT>
typename GridT::Ptr requireGrid(const openvdb::GridPtrVec& grids, const std::string& name, const std::string& path) {
    for (const auto& grid : grids) {
        if (grid->getName() != name) continue;
        auto typed = openvdb::gridPtrCast<GridT>(grid);
        if (!typed)
            throw InputError(path + ": grid '" + name + "' has type " + grid->valueType() + ", expected " +
                             openvdb::typeNameAsString<typename GridT::ValueType>());
        return typed;
    }
    throw InputError(path + ": no grid named '" + name + "' (not a voxgi geometry volume)");
}

bool hasGrid(const openvdb::GridPtrVec& grids, const std::string& name) {
    for (const auto& grid : grids)
        if (grid->getName() == name) return true;
    return false;
}

std::string stringMeta(const openvdb::MetaMap& meta, const std::string& key) {
    auto m = meta.getMetadata<openvdb::StringMetadata>(key);
    return m ? m->value() : std::string();
}

}  // namespace

SparseGeometryVolume readGeometryVolume(const std::string& path) {
    detail::VdbFileContents file = detail::readVdbFile(path);
    const openvdb::GridPtrVec& grids = file.grids;
    const openvdb::MetaMap::Ptr& meta = file.meta;
    SparseGeometryVolume volume;
    detail::GeometryGrids& g = volume.grids();
    g.sourceHash = stringMeta(*meta, "voxgi_source_hash");
    g.blockerFit = stringMeta(*meta, "voxgi_blocker_fit") == "projection" ? BlockerFit::Projection : BlockerFit::PlaneExact;
    for (int level = 0; level == 0 || hasGrid(grids, gridName("occupancy", level)); ++level) {
        detail::LevelFileGrids l;
        l.occupancy = requireGrid<openvdb::BoolGrid>(grids, gridName("occupancy", level), path);
        l.albedo = requireGrid<openvdb::Vec3fGrid>(grids, gridName("albedo", level), path);
        l.normal = requireGrid<openvdb::Vec3fGrid>(grids, gridName("normal", level), path);
        // Optional: files from before revision 4 estimate it (LevelFileGrids).
        if (hasGrid(grids, gridName("projected_coverage", level)))
            l.projected = requireGrid<openvdb::Vec3fGrid>(grids, gridName("projected_coverage", level), path);
        for (int c = 0; c < 4; ++c)
            l.blocker[std::size_t(c)] =
                requireGrid<openvdb::FloatGrid>(grids, gridName("blocker_sh" + std::to_string(c), level), path);
        if (!(l.occupancy->voxelSize()[0] > 0.0))
            throw InputError(path + ": grid '" + l.occupancy->getName() + "' has no voxel size");
        g.levels.push_back(detail::compactLevel(std::move(l), g.blockerFit, path));
    }
    if (hasGrid(grids, "sdf")) g.sdf = requireGrid<openvdb::FloatGrid>(grids, "sdf", path);
    return volume;
}

SparseGeometryVolume loadOrBuildGeometryVolume(const Scene& scene, const VoxelizeSettings& settings,
                                         const std::string& cacheDir, bool* fromCache) {
    const std::string hash = geometryHash(scene, settings);
    const std::string path = (std::filesystem::path(cacheDir) / ("geometry-" + hash + ".vdb")).string();
    if (fromCache) *fromCache = false;
    if (std::filesystem::is_regular_file(path)) {
        try {
            SparseGeometryVolume cached = readGeometryVolume(path);
            if (cached.sourceHash() == hash && cached.levelCount() == settings.levels && cached.hasSdf() == settings.sdf) {
                if (fromCache) *fromCache = true;
                return cached;
            }
        } catch (const InputError&) {
            // A damaged cache entry is rebuilt below.
        }
    }
    SparseGeometryVolume volume = voxelizeScene(scene, settings);
    std::error_code ec;
    std::filesystem::create_directories(cacheDir, ec);
    if (ec) throw InputError(cacheDir + ": cannot create cache directory (" + ec.message() + ")");
    writeGeometryVolume(path, volume);
    return volume;
}

}  // namespace voxgi
