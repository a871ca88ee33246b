#include "volumes/vdb_inspect.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include <openvdb/openvdb.h>

#include "scenes/errors.h"
#include "volumes/detail/vdb_file.h"

namespace voxgi {

namespace {

using OpenedFile = detail::VdbFileContents;

OpenedFile openFile(const std::string& path) { return detail::readVdbFile(path); }

std::vector<std::pair<std::string, std::string>> metaText(const openvdb::MetaMap& meta) {
    std::vector<std::pair<std::string, std::string>> out;
    for (auto it = meta.beginMeta(); it != meta.endMeta(); ++it) out.push_back({it->first, it->second->str()});
    return out;
}

// Calls fn(typed grid) for the value types voxgi and common tools write; false otherwise.
template <typename Fn>
bool withTypedGrid(const openvdb::GridBase::Ptr& grid, Fn&& fn) {
    if (auto g = openvdb::gridPtrCast<openvdb::FloatGrid>(grid)) return fn(*g), true;
    if (auto g = openvdb::gridPtrCast<openvdb::DoubleGrid>(grid)) return fn(*g), true;
    if (auto g = openvdb::gridPtrCast<openvdb::Int32Grid>(grid)) return fn(*g), true;
    if (auto g = openvdb::gridPtrCast<openvdb::Vec3fGrid>(grid)) return fn(*g), true;
    if (auto g = openvdb::gridPtrCast<openvdb::Vec3dGrid>(grid)) return fn(*g), true;
    if (auto g = openvdb::gridPtrCast<openvdb::BoolGrid>(grid)) return fn(*g), true;
    if (auto g = openvdb::gridPtrCast<openvdb::MaskGrid>(grid)) return fn(*g), true;
    return false;
}

template <typename T> double scalarOf(const T& v) {
    if constexpr (std::is_same_v<T, bool> || std::is_same_v<T, openvdb::ValueMask>) return 1.0;
    else if constexpr (openvdb::VecTraits<T>::IsVec) return double(v.length());
    else return double(v);
}

}  // namespace

VdbFileInfo inspectVdbFile(const std::string& path) {
    OpenedFile f = openFile(path);
    VdbFileInfo info;
    info.metadata = metaText(*f.meta);
    for (const auto& grid : f.grids) {
        VdbGridInfo g;
        g.name = grid->getName();
        g.valueType = grid->valueType();
        g.gridClass = openvdb::GridBase::gridClassToString(grid->getGridClass());
        openvdb::Vec3d vs = grid->voxelSize();
        g.voxelSize = {vs.x(), vs.y(), vs.z()};
        g.activeVoxels = grid->activeVoxelCount();
        openvdb::CoordBBox box = grid->evalActiveVoxelBoundingBox();
        if (!box.empty()) {
            g.indexBox.min = {box.min().x(), box.min().y(), box.min().z()};
            g.indexBox.max = {box.max().x(), box.max().y(), box.max().z()};
            openvdb::BBoxd world = grid->transform().indexToWorld(
                openvdb::BBoxd(box.min().asVec3d() - 0.5, box.max().asVec3d() + 0.5));
            g.worldMin = {world.min().x(), world.min().y(), world.min().z()};
            g.worldMax = {world.max().x(), world.max().y(), world.max().z()};
        }
        g.memoryBytes = grid->memUsage();
        g.metadata = metaText(*grid);
        info.grids.push_back(std::move(g));
    }
    return info;
}

std::vector<VdbHistogram> vdbHistograms(const std::string& path, int bins) {
    OpenedFile f = openFile(path);
    bins = std::max(1, bins);
    std::vector<VdbHistogram> out;
    for (const auto& grid : f.grids) {
        VdbHistogram h;
        h.grid = grid->getName();
        bool known = withTypedGrid(grid, [&](const auto& g) {
            using T = typename std::decay_t<decltype(g)>::ValueType;
            constexpr bool isBool = std::is_same_v<T, bool> || std::is_same_v<T, openvdb::ValueMask>;
            h.quantity = isBool ? "active" : (openvdb::VecTraits<T>::IsVec ? "length" : "value");
            double lo = std::numeric_limits<double>::infinity(), hi = -lo;
            for (auto it = g.cbeginValueOn(); it; ++it) {
                double v = scalarOf(*it);
                if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
            }
            if (!(lo <= hi)) lo = hi = 0.0;
            h.min = lo;
            h.max = hi;
            h.counts.assign(isBool ? 1 : std::size_t(bins), 0);
            for (auto it = g.cbeginValueOn(); it; ++it) {
                double v = scalarOf(*it);
                if (!std::isfinite(v)) continue;
                std::size_t b = hi > lo ? std::size_t((v - lo) / (hi - lo) * double(h.counts.size())) : 0;
                ++h.counts[std::min(b, h.counts.size() - 1)];
            }
        });
        if (known) out.push_back(std::move(h));
    }
    return out;
}

namespace {

std::uint8_t toByte(double v) { return std::uint8_t(std::clamp(v, 0.0, 1.0) * 255.0 + 0.5); }

double srgbEncode(double c) {
    c = std::clamp(c, 0.0, 1.0);
    return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
}

}  // namespace

VdbSlice sliceVdbFile(const std::string& path, const std::string& gridName, int axis, double world) {
    OpenedFile f = openFile(path);
    if (f.grids.empty()) throw InputError(path + ": holds no grids to slice");
    openvdb::GridBase::Ptr grid;
    const std::string wanted = gridName.empty() ? "albedo" : gridName;
    for (const auto& g : f.grids)
        if (g->getName() == wanted) grid = g;
    if (!grid && gridName.empty()) grid = f.grids.front();
    if (!grid) throw InputError("--grid: no grid named '" + gridName + "' in " + path);
    openvdb::CoordBBox box = grid->evalActiveVoxelBoundingBox();
    if (box.empty()) throw InputError(path + ": grid '" + grid->getName() + "' has no active voxels to slice");

    VdbSlice slice;
    slice.grid = grid->getName();
    openvdb::Vec3d worldPoint(0.0);
    worldPoint[axis] = world;
    // Outside the active voxels the slice would be empty; far outside, lround overflows int.
    const double plane = std::round(grid->transform().worldToIndex(worldPoint)[axis]);
    if (!(plane >= double(box.min()[axis]) && plane <= double(box.max()[axis]))) {
        const openvdb::Vec3d lo = grid->transform().indexToWorld(box.min().asVec3d()),
                             hi = grid->transform().indexToWorld(box.max().asVec3d());
        char why[160];
        std::snprintf(why, sizeof why, "--slice %c=%g: outside grid '%s' (%g to %g)", 'x' + axis, world,
                      grid->getName().c_str(), lo[axis], hi[axis]);
        throw InputError(why);
    }
    slice.indexPlane = int(plane);
    const int u = axis == 0 ? 1 : 0, v = axis == 2 ? 1 : 2;
    slice.width = box.max()[u] - box.min()[u] + 1;
    slice.height = box.max()[v] - box.min()[v] + 1;
    if (std::int64_t(slice.width) * slice.height > (std::int64_t(1) << 26))
        throw InputError(path + ": slice of " + std::to_string(slice.width) + "x" + std::to_string(slice.height) +
                         " voxels is too large for an image");
    slice.rgb.assign(std::size_t(slice.width) * std::size_t(slice.height) * 3, 24);
    std::string role;
    if (auto m = grid->getMetadata<openvdb::StringMetadata>("voxgi_class")) role = m->value();
    const bool isAlbedo = role == "albedo" || grid->getName().rfind("albedo", 0) == 0;

    bool known = withTypedGrid(grid, [&](const auto& g) {
        using T = typename std::decay_t<decltype(g)>::ValueType;
        auto acc = g.getConstAccessor();
        double lo = std::numeric_limits<double>::infinity(), hi = -lo;
        auto at = [&](int x, int y) {
            openvdb::Coord c;
            c[axis] = slice.indexPlane;
            c[u] = box.min()[u] + x;
            c[v] = box.max()[v] - y;
            return c;
        };
        if constexpr (!openvdb::VecTraits<T>::IsVec) {
            for (int y = 0; y < slice.height; ++y)
                for (int x = 0; x < slice.width; ++x) {
                    T value;
                    if (acc.probeValue(at(x, y), value)) {
                        double s = scalarOf(value);
                        if (std::isfinite(s)) lo = std::min(lo, s), hi = std::max(hi, s);
                    }
                }
            if (!(lo <= hi)) lo = hi = 0.0;
            slice.valueMin = lo;
            slice.valueMax = hi;
        }
        for (int y = 0; y < slice.height; ++y)
            for (int x = 0; x < slice.width; ++x) {
                T value;
                if (!acc.probeValue(at(x, y), value)) continue;
                std::uint8_t* px = &slice.rgb[(std::size_t(y) * std::size_t(slice.width) + std::size_t(x)) * 3];
                glm::dvec3 rgb;
                if constexpr (std::is_same_v<T, bool> || std::is_same_v<T, openvdb::ValueMask>) {
                    rgb = glm::dvec3(1.0);
                } else if constexpr (openvdb::VecTraits<T>::IsVec) {
                    glm::dvec3 w(value[0], value[1], value[2]);
                    rgb = isAlbedo ? glm::dvec3(srgbEncode(w.x), srgbEncode(w.y), srgbEncode(w.z)) : 0.5 + 0.5 * w;
                } else {
                    double t = hi > lo ? (scalarOf(value) - lo) / (hi - lo) : 0.5;
                    rgb = glm::dvec3(t, 0.25 * (1.0 - std::abs(2.0 * t - 1.0)) + 0.1, 1.0 - t);
                }
                px[0] = toByte(rgb.x);
                px[1] = toByte(rgb.y);
                px[2] = toByte(rgb.z);
            }
    });
    if (!known) throw InputError(path + ": grid '" + grid->getName() + "' has value type " + grid->valueType() +
                                 ", which slices do not support");
    return slice;
}

}  // namespace voxgi
