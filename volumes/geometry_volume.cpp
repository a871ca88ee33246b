#include "volumes/geometry_volume.h"

#include <algorithm>
#include <chrono>

#include <openvdb/tools/Morphology.h>

#include "scenes/errors.h"
#include "volumes/detail/geometry_grids.h"
#include "volumes/detail/grid_build.h"
#include "volumes/detail/voxelizer.h"
#include "volumes/openvdb_setup.h"
#include "volumes/detail/sdf_fill.h"

namespace voxgi {

namespace detail {

openvdb::GridPtrVec GeometryGrids::all() const {
    openvdb::GridPtrVec grids;
    for (const LevelGrids& l : levels) {
        grids.push_back(l.occupancy);
        grids.push_back(l.albedo);
        grids.push_back(l.normal);
        for (const auto& b : l.blocker) grids.push_back(b);
    }
    if (sdf) grids.push_back(sdf);
    return grids;
}

openvdb::math::Transform::Ptr voxelTransform(double voxelSize) {
    auto xform = openvdb::math::Transform::createLinearTransform(voxelSize);
    xform->postTranslate(openvdb::Vec3d(0.5 * voxelSize));
    return xform;
}

namespace {
void annotate(openvdb::GridBase& grid, const std::string& name, const char* role, int level, double voxelSize,
              const GeometryGrids& g) {
    grid.setName(name);
    grid.insertMeta("voxgi_class", openvdb::StringMetadata(role));
    grid.insertMeta("voxgi_level", openvdb::Int32Metadata(level));
    grid.insertMeta("voxgi_voxel_size", openvdb::DoubleMetadata(voxelSize));
    grid.insertMeta("voxgi_source_hash", openvdb::StringMetadata(g.sourceHash));
    grid.insertMeta("voxgi_version", openvdb::StringMetadata(VOXGI_VERSION));
}
}  // namespace

void annotateGrids(GeometryGrids& g) {
    for (std::size_t i = 0; i < g.levels.size(); ++i) {
        LevelGrids& l = g.levels[i];
        const int level = int(i);
        annotate(*l.occupancy, gridName("occupancy", level), "occupancy", level, l.voxelSize, g);
        l.occupancy->setGridClass(openvdb::GRID_FOG_VOLUME);
        annotate(*l.albedo, gridName("albedo", level), "albedo", level, l.voxelSize, g);
        l.albedo->setGridClass(openvdb::GRID_UNKNOWN);
        l.albedo->setVectorType(openvdb::VEC_INVARIANT);
        annotate(*l.normal, gridName("normal", level), "normal", level, l.voxelSize, g);
        l.normal->setGridClass(openvdb::GRID_UNKNOWN);
        l.normal->setVectorType(openvdb::VEC_COVARIANT);
        for (int c = 0; c < 4; ++c) {
            openvdb::FloatGrid& b = *l.blocker[c];
            annotate(b, gridName("blocker_sh" + std::to_string(c), level), "blocker", level, l.voxelSize, g);
            b.setGridClass(openvdb::GRID_UNKNOWN);
            b.insertMeta("voxgi_sh_index", openvdb::Int32Metadata(c));
            b.insertMeta("voxgi_sh_convention",
                         openvdb::StringMetadata("B(w)=clamp(sum c_i Y_i(w),0,1); (c0,c1,c2,c3)=(Y00,Y1-1,Y10,Y11); "
                                                 "Y00=0.282094792, Y1-1=-0.488602512*y, Y10=0.488602512*z, "
                                                 "Y11=-0.488602512*x"));
            b.insertMeta("voxgi_blocker_fit", openvdb::StringMetadata(blockerFitName(g.blockerFit)));
        }
    }
    if (g.sdf) {
        annotate(*g.sdf, "sdf", "sdf", 0, g.levels.empty() ? 0.0 : g.levels[0].voxelSize, g);
        g.sdf->setGridClass(openvdb::GRID_LEVEL_SET);
    }
}

}  // namespace detail

std::string gridName(const std::string& base, int level) {
    return level == 0 ? base : base + "_L" + std::to_string(level);
}

SparseGeometryVolume::SparseGeometryVolume() : grids_(std::make_unique<detail::GeometryGrids>()) {}
SparseGeometryVolume::~SparseGeometryVolume() = default;
SparseGeometryVolume::SparseGeometryVolume(SparseGeometryVolume&&) noexcept = default;
SparseGeometryVolume& SparseGeometryVolume::operator=(SparseGeometryVolume&&) noexcept = default;

detail::GeometryGrids& SparseGeometryVolume::grids() { return *grids_; }
const detail::GeometryGrids& SparseGeometryVolume::grids() const { return *grids_; }

int SparseGeometryVolume::levelCount() const { return int(grids_->levels.size()); }
bool SparseGeometryVolume::hasSdf() const { return bool(grids_->sdf); }
const std::string& SparseGeometryVolume::sourceHash() const { return grids_->sourceHash; }
const VoxelizeStats& SparseGeometryVolume::stats() const { return grids_->stats; }

namespace {
const detail::LevelGrids& levelOf(const detail::GeometryGrids& g, int level) {
    if (level < 0 || level >= int(g.levels.size()))
        throw std::out_of_range("SparseGeometryVolume: no level " + std::to_string(level));
    return g.levels[std::size_t(level)];
}
openvdb::Coord coord(const glm::ivec3& v) { return openvdb::Coord(v.x, v.y, v.z); }
}  // namespace

float SparseGeometryVolume::voxelSize(int level) const { return float(levelOf(*grids_, level).voxelSize); }

bool SparseGeometryVolume::occupied(const glm::ivec3& ijk, int level) const {
    return levelOf(*grids_, level).occupancy->tree().isValueOn(coord(ijk));
}

glm::vec4 SparseGeometryVolume::blockerSH(const glm::ivec3& ijk, int level) const {
    const auto& l = levelOf(*grids_, level);
    glm::vec4 sh;
    for (int c = 0; c < 4; ++c) sh[c] = l.blocker[c]->tree().getValue(coord(ijk));
    return sh;
}

glm::vec3 SparseGeometryVolume::albedo(const glm::ivec3& ijk, int level) const {
    auto v = levelOf(*grids_, level).albedo->tree().getValue(coord(ijk));
    return {v.x(), v.y(), v.z()};
}

glm::vec3 SparseGeometryVolume::normal(const glm::ivec3& ijk, int level) const {
    auto v = levelOf(*grids_, level).normal->tree().getValue(coord(ijk));
    return {v.x(), v.y(), v.z()};
}

float SparseGeometryVolume::sdf(const glm::ivec3& ijk) const {
    if (!grids_->sdf) throw std::logic_error("SparseGeometryVolume: no sdf grid");
    return grids_->sdf->tree().getValue(coord(ijk));
}

std::uint64_t SparseGeometryVolume::activeVoxelCount(int level) const {
    return levelOf(*grids_, level).occupancy->activeVoxelCount();
}

IndexBox SparseGeometryVolume::indexBounds(int level) const {
    openvdb::CoordBBox box = levelOf(*grids_, level).occupancy->evalActiveVoxelBoundingBox();
    IndexBox b;
    if (box.empty()) return b;
    b.min = {box.min().x(), box.min().y(), box.min().z()};
    b.max = {box.max().x(), box.max().y(), box.max().z()};
    return b;
}

glm::vec3 SparseGeometryVolume::voxelCenter(const glm::ivec3& ijk, int level) const {
    return (glm::vec3(ijk) + 0.5f) * voxelSize(level);
}

glm::ivec3 SparseGeometryVolume::voxelAt(const glm::vec3& world, int level) const {
    return glm::ivec3(glm::floor(world / voxelSize(level)));
}

std::vector<Brick> SparseGeometryVolume::activeBricks(int level, int dilateVoxels) const {
    const auto& l = levelOf(*grids_, level);
    openvdb::BoolTree tree(l.occupancy->tree());
    if (dilateVoxels > 0)
        openvdb::tools::dilateActiveValues(tree, dilateVoxels, openvdb::tools::NN_FACE_EDGE_VERTEX,
                                           openvdb::tools::IGNORE_TILES);
    std::vector<Brick> bricks;
    const float h = float(l.voxelSize);
    for (auto leaf = tree.cbeginLeaf(); leaf; ++leaf) {
        if (leaf->isEmpty()) continue;
        Brick b;
        b.origin = {leaf->origin().x(), leaf->origin().y(), leaf->origin().z()};
        b.worldMin = glm::vec3(b.origin) * h;
        b.worldMax = glm::vec3(b.origin + 8) * h;
        bricks.push_back(b);
    }
    std::sort(bricks.begin(), bricks.end(), [](const Brick& a, const Brick& b) {
        return std::tie(a.origin.z, a.origin.y, a.origin.x) < std::tie(b.origin.z, b.origin.y, b.origin.x);
    });
    return bricks;
}

std::uint64_t SparseGeometryVolume::memoryBytes() const {
    std::uint64_t bytes = 0;
    for (const auto& grid : grids_->all()) bytes += grid->memUsage();
    return bytes;
}

SparseGeometryVolume voxelizeScene(const Scene& scene, const VoxelizeSettings& settings) {
    if (!(settings.voxelSize > 0.0f) || !std::isfinite(settings.voxelSize))
        throw InputError("--voxel-size: must be a positive finite number");
    // OpenVDB refuses transforms whose scale determinant is below ~3e-15.
    if (settings.voxelSize < 2e-5f)
        throw InputError("--voxel-size " + std::to_string(settings.voxelSize) +
                         ": below 2e-5, the smallest voxel OpenVDB transforms accept; scale the scene up instead");
    if (settings.levels < 1 || settings.levels > 16) throw InputError("--levels: must be in [1, 16]");
    initializeOpenVdb();
    auto start = std::chrono::steady_clock::now();
    SparseGeometryVolume volume;
    detail::GeometryGrids& g = volume.grids();
    g.blockerFit = settings.blockerFit;
    g.sourceHash = geometryHash(scene, settings);
    detail::AccumLevel level = detail::voxelizeTriangles(scene, settings, g.stats);
    for (int l = 0; l < settings.levels; ++l) {
        // The coarser level reads this one's sums before they are finalized.
        detail::AccumLevel coarser = l + 1 < settings.levels ? detail::downsample(level) : detail::AccumLevel{};
        g.levels.push_back(detail::buildLevelGrids(std::move(level), double(settings.voxelSize) * double(1 << l),
                                                   settings.blockerFit));
        level = std::move(coarser);
    }
    if (settings.sdf) g.sdf = detail::buildSdf(scene, settings);
    detail::annotateGrids(g);
    g.stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return volume;
}

}  // namespace voxgi
