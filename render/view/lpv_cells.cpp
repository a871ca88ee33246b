// Reads the LPV dump (gi/lpv/lpv_dump.h grid names) back into spheres for the overlay.
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>

#include <openvdb/openvdb.h>

#include "gi/lpv/lpv_technique.h"
#include "render/view/sphere_set.h"
#include "volumes/openvdb_setup.h"

namespace voxgi::view {

SphereSet lpvCellSpheres(GiTechnique* technique, int cascade, int stride, float exposureStops,
                         const std::string& scratchPath) {
    SphereSet set;
    set.sh = true;
    auto* lpv = dynamic_cast<LpvTechnique*>(technique);
    if (!lpv) return set;
    lpv->dumpVdb(scratchPath);
    initializeOpenVdb();
    openvdb::io::File file(scratchPath);
    file.open();
    openvdb::FloatGrid::Ptr grids[3][4];
    const char* channels[3] = {"r", "g", "b"};
    for (int c = 0; c < 3; ++c)
        for (int k = 0; k < 4; ++k) {
            std::string name = std::string("lpv_") + channels[c] + "_L" + std::to_string(cascade) + "_sh" + std::to_string(k);
            if (!file.hasGrid(name)) {
                file.close();
                std::filesystem::remove(scratchPath);
                return set;  // no such cascade
            }
            grids[c][k] = openvdb::gridPtrCast<openvdb::FloatGrid>(file.readGrid(name));
        }
    file.close();
    std::filesystem::remove(scratchPath);

    const openvdb::math::Transform& xform = grids[0][0]->transform();
    float cellSize = float(xform.voxelSize()[0]);
    // Cells holding light in any channel: the union of the three sh0 grids' active voxels.
    openvdb::FloatGrid::Ptr any = grids[0][0]->deepCopy();
    any->topologyUnion(*grids[1][0]);
    any->topologyUnion(*grids[2][0]);
    std::array<openvdb::FloatGrid::ConstAccessor, 12> access{
        grids[0][0]->getConstAccessor(), grids[0][1]->getConstAccessor(), grids[0][2]->getConstAccessor(),
        grids[0][3]->getConstAccessor(), grids[1][0]->getConstAccessor(), grids[1][1]->getConstAccessor(),
        grids[1][2]->getConstAccessor(), grids[1][3]->getConstAccessor(), grids[2][0]->getConstAccessor(),
        grids[2][1]->getConstAccessor(), grids[2][2]->getConstAccessor(), grids[2][3]->getConstAccessor()};
    float brightest = 0.0f;
    for (auto it = any->cbeginValueOn(); it; ++it) {
        openvdb::Coord ijk = it.getCoord();
        auto onStride = [&](int v) { return ((v % stride) + stride) % stride == 0; };
        if (!onStride(ijk.x()) || !onStride(ijk.y()) || !onStride(ijk.z())) continue;
        SphereInstance s;
        openvdb::Vec3d p = xform.indexToWorld(ijk);
        s.centerRadius = glm::vec4(float(p.x()), float(p.y()), float(p.z()), 0.3f * cellSize * float(stride));
        glm::vec4* out[3] = {&s.r, &s.g, &s.b};
        for (int c = 0; c < 3; ++c)
            for (int k = 0; k < 4; ++k) (*out[c])[k] = access[std::size_t(c * 4 + k)].getValue(ijk);
        brightest = std::max({brightest, s.r.x, s.g.x, s.b.x});
        set.spheres.push_back(s);
    }
    // The mean intensity over directions is c0 * Y00.
    set.scale = brightest > 0.0f ? std::exp2(exposureStops) / (0.282094792f * brightest) : 1.0f;
    return set;
}

}  // namespace voxgi::view
