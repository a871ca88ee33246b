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

openvdb::math::Transform::Ptr voxelTransform(double voxelSize) {
    auto xform = openvdb::math::Transform::createLinearTransform(voxelSize);
    xform->postTranslate(openvdb::Vec3d(0.5 * voxelSize));
    return xform;
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
    return levelOf(*grids_, level).occupancy->constTree().isValueOn(coord(ijk));
}

glm::vec4 SparseGeometryVolume::blockerSH(const glm::ivec3& ijk, int level) const {
    const auto& l = levelOf(*grids_, level);
    const std::int64_t i = l.attributeIndex(coord(ijk));
    if (i < 0) return glm::vec4(0.0f);
    const glm::vec4& n = l.normalC0[std::size_t(i)];
    return voxgi::blockerSH(n.w, glm::vec3(n), grids_->blockerFit);
}

glm::vec3 SparseGeometryVolume::albedo(const glm::ivec3& ijk, int level) const {
    const auto& l = levelOf(*grids_, level);
    const std::int64_t i = l.attributeIndex(coord(ijk));
    return i < 0 ? glm::vec3(0.0f) : detail::fromHalves(l.albedo[std::size_t(i)]);
}

glm::vec3 SparseGeometryVolume::normal(const glm::ivec3& ijk, int level) const {
    const auto& l = levelOf(*grids_, level);
    const std::int64_t i = l.attributeIndex(coord(ijk));
    return i < 0 ? glm::vec3(0.0f) : glm::vec3(l.normalC0[std::size_t(i)]);
}

glm::vec3 SparseGeometryVolume::projectedCoverage(const glm::ivec3& ijk, int level) const {
    const auto& l = levelOf(*grids_, level);
    const std::int64_t i = l.attributeIndex(coord(ijk));
    return i < 0 ? glm::vec3(0.0f) : detail::fromHalves(l.projected[std::size_t(i)]);
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
    std::uint64_t bytes = sizeof(detail::GeometryGrids);
    for (const detail::LevelGrids& l : grids_->levels) bytes += sizeof(detail::LevelGrids) + l.memoryBytes();
    if (grids_->sdf) bytes += grids_->sdf->memUsage();
    return bytes;
}

SparseGeometryVolume voxelizeScene(const Scene& scene, const VoxelizeSettings& settings) {
    if (!(settings.voxelSize > 0.0f) || !std::isfinite(settings.voxelSize))
        throw InputError("--voxel-size: must be a positive finite number");
    if (settings.voxelSize < kSmallestVoxelSize)
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
    g.stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return volume;
}

}  // namespace voxgi
