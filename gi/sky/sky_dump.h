// Writes the sky-lighting volume (gi/sky/sky_volume.h) as OpenVDB grids: for colour C in
// {r, g, b} and k = 0..8, the FloatGrid `sky_sh_C_<k>` of the irradiance SH coefficient k
// (W/m^2, gi/sh/sh.h's order, already convolved with the clamped cosine) at the cell centres,
// active only at cells in open space (cells inside geometry hold nothing). Metadata: cell_size,
// sh_coefficient, units, rays.
#pragma once

#include <string>

namespace voxgi {

class SkyVolume;

void writeSkyVolumeVdb(const std::string& path, const SkyVolume& volume);

}  // namespace voxgi
