// Writes the LPV state as OpenVDB grids readable by vdb_print and any OpenVDB tool:
// per cascade L and colour C in {r, g, b}, the FloatGrids `lpv_C_L<L>_sh<k>` (k = 0..3, the
// 2-band SH order of gi/sh/sh.h) of the propagated intensity (W/sr), placed at the cell
// centres; and the geometry volume at the cell corners (half a cell off): `blocker_L<L>_sh<k>`
// and the Vec3 grid `albedo_L<L>`. Metadata: cascade, cell_size, sh_coefficient, units.
#pragma once

#include <string>
#include <vector>

#include "gi/lpv/light_volume.h"
#include "gi/lpv/ordinates.h"

namespace voxgi {

void writeLpvVdb(const std::string& path, const std::vector<LightVolume>& light,
                 const std::vector<BlockerVolume>& geometry);

// lpv.transport=ordinates: per cascade L, the Vec3 grids `irradiance_<face>_L<L>` (face px, nx, py,
// ny, pz, nz: a receiver facing +x, -x, ...; W/m^2, cell-centred), the irradiance cube the apply
// pass reads (ring and inner light summed). Each stored brick becomes one leaf node, its values
// copied in the leaf's order (shaders/shared/light_bricks.h); cells without light are inactive.
struct OrdinatesDump {
    const OrdinatesTransport* transport = nullptr;  // its grid and bricks
    IrradianceBricks irradiance;
};
void writeOrdinatesVdb(const std::string& path, const std::vector<OrdinatesDump>& cascades);

}  // namespace voxgi
