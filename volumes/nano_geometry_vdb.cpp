#include "volumes/nano_geometry_vdb.h"

#include <cstdint>

#include <nanovdb/NanoVDB.h>
#include <nanovdb/util/NanoToOpenVDB.h>

#include "volumes/detail/geometry_grids.h"
#include "volumes/nano_geometry.h"

namespace voxgi {

namespace {
template <typename Value>
openvdb::GridBase::Ptr toOpenVdb(const NanoGeometry& g, std::uint32_t offset, const std::string& name,
                                 const std::string& meaning) {
    const auto* bytes = reinterpret_cast<const unsigned char*>(g.words.data());
    const auto& nano = *reinterpret_cast<const nanovdb::NanoGrid<Value>*>(bytes + offset);
    openvdb::GridBase::Ptr grid = nanovdb::nanoToOpenVDB(nano);
    grid->setName(name);
    // The NanoVDB grids are in index space (the shaders scale by the voxel size).
    grid->setTransform(detail::voxelTransform(double(g.voxelSize)));
    grid->insertMeta("voxgi_meaning", openvdb::StringMetadata(meaning));
    return grid;
}
}  // namespace

openvdb::GridPtrVec nanoGeometryGrids(const NanoGeometry& g, const std::string& prefix) {
    openvdb::GridPtrVec grids;
    if (g.words.empty()) return grids;
    grids.push_back(toOpenVdb<nanovdb::Vec3f>(g, g.normalGrid, prefix + "normal",
                                              "mean normal times consistency |sum a n| / sum a"));
    grids.push_back(toOpenVdb<nanovdb::Vec3f>(g, g.albedoGrid, prefix + "albedo", "diffuse albedo, linear"));
    if (g.offsetGrid != 0)
        grids.push_back(toOpenVdb<float>(g, g.offsetGrid, prefix + "surface_offset",
                                         "m along the normal from the voxel centre to the surface"));
    return grids;
}

}  // namespace voxgi
