#include "gi/sky/sky_dump.h"

#include <openvdb/openvdb.h>

#include "gi/sky/sky_volume.h"
#include "volumes/openvdb_file.h"
#include "volumes/openvdb_setup.h"

namespace voxgi {

void writeSkyVolumeVdb(const std::string& path, const SkyVolume& volume) {
    initializeOpenVdb();
    // Index (i, j, k) is the cell centred at origin + (i, j, k) * cell.
    auto xform = openvdb::math::Transform::createLinearTransform(double(volume.cellSize()));
    const glm::vec3 o = volume.origin();
    xform->postTranslate(openvdb::Vec3d(double(o.x), double(o.y), double(o.z)));
    const glm::ivec3 d = volume.dims();
    openvdb::GridPtrVec grids;
    const char* colours[3] = {"r", "g", "b"};
    for (int c = 0; c < 3; ++c)
        for (int k = 0; k < 9; ++k) {
            auto grid = openvdb::FloatGrid::create(0.0f);
            grid->setTransform(xform->copy());
            grid->setName("sky_sh_" + std::string(colours[c]) + "_" + std::to_string(k));
            grid->setGridClass(openvdb::GRID_FOG_VOLUME);
            grid->insertMeta("cell_size", openvdb::FloatMetadata(volume.cellSize()));
            grid->insertMeta("sh_coefficient", openvdb::Int32Metadata(k));
            grid->insertMeta("units", openvdb::StringMetadata("W/m^2 (irradiance SH)"));
            grid->insertMeta("creator", openvdb::StringMetadata("voxgi " VOXGI_VERSION));
            auto acc = grid->getAccessor();
            const int flat = 9 * c + k;  // the packed layout: colour-major, then the validity
            for (int z = 0; z < d.z; ++z)
                for (int y = 0; y < d.y; ++y)
                    for (int x = 0; x < d.x; ++x) {
                        const glm::vec4* cell = volume.cell({x, y, z});
                        if (!cell || cell[6].w <= 0.0f) continue;
                        acc.setValue(openvdb::Coord(x, y, z), cell[flat / 4][flat % 4]);
                    }
            grids.push_back(grid);
        }
    writeVdbFile(path, grids);
}

}  // namespace voxgi
