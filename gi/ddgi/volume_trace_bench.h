// `voxgi bench ddgi`'s GL section on probe rays cast through the NanoVDB geometry volume
// (VolumeTracerGl) at several voxel sizes: memory, GPU time and rays per second.
#pragma once

namespace voxgi {

class DdgiSystem;

// Every probe's rays of the system's last frame, through volumes with 4, 8 and 16 voxels per
// smallest probe spacing. Needs a current GL context.
void printVolumeTraceBench(const DdgiSystem& ddgi);

}  // namespace voxgi
