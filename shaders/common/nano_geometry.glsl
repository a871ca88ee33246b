// Ray casting through a geometry volume level uploaded as NanoVDB (volumes/nano_geometry.h):
// the first occupied voxel along a ray, by a DDA that steps voxel by voxel inside allocated
// leaves and jumps over the empty nodes and tiles of the tree in one step each (PNanoVDB's
// readaccessor_get_dim: 1 inside a leaf, 8, 128 or 4096 across an empty node). Define
// NANO_GEOMETRY_BINDING (the storage-buffer binding of the grids) before including.
layout(std430, binding = NANO_GEOMETRY_BINDING) readonly buffer NanoGeometryGrids { uint pnanovdb_buf_data[]; };
#define PNANOVDB_GLSL
#include <nanovdb/PNanoVDB.h>

uniform uint uNanoNormalGrid;  // byte offsets of the grids in the buffer
uniform uint uNanoAlbedoGrid;
uniform uint uNanoOffsetGrid;  // 0: none
uniform float uNanoVoxelSize;  // world size of a voxel: voxel ijk covers [ijk, ijk + 1] * size

// Safety cap on DDA steps per ray (a ray crossing a 4096^3 index box in single voxels makes 12288).
const int kNanoMaxSteps = 16384;

pnanovdb_readaccessor_t nanoAccessor(uint gridOffset) {
    pnanovdb_buf_t buf = pnanovdb_buf_t(0u);
    pnanovdb_grid_handle_t grid;
    grid.address.byte_offset = gridOffset;
    pnanovdb_readaccessor_t acc;
    pnanovdb_readaccessor_init(acc, pnanovdb_tree_get_root(buf, pnanovdb_grid_get_tree(buf, grid)));
    return acc;
}

vec3 nanoReadVec3(inout pnanovdb_readaccessor_t acc, ivec3 ijk) {
    pnanovdb_buf_t buf = pnanovdb_buf_t(0u);
    pnanovdb_address_t a = pnanovdb_readaccessor_get_value_address(PNANOVDB_GRID_TYPE_VEC3F, buf, acc, ijk);
    return vec3(pnanovdb_read_float(buf, a), pnanovdb_read_float(buf, pnanovdb_address_offset(a, 4u)),
                pnanovdb_read_float(buf, pnanovdb_address_offset(a, 8u)));
}

float nanoReadFloat(inout pnanovdb_readaccessor_t acc, ivec3 ijk) {
    pnanovdb_buf_t buf = pnanovdb_buf_t(0u);
    return pnanovdb_read_float(buf, pnanovdb_readaccessor_get_value_address(PNANOVDB_GRID_TYPE_FLOAT, buf, acc, ijk));
}

// Voxels whose mean normal is shorter than this (consistency |sum a n| / sum a) have faces
// looking every way (a thin wall's two sides, a column): they have no back side.
const float kNanoOneSidedConsistency = 0.5;

// Voxels at least this consistent are traced as their surface plane (nanoFirstHit).
const float kNanoPlanarConsistency = 0.9;

// The face a ray along `dir` meets in a voxel of mean normal `mean` (the normal grid's value):
// true for a back face; `n` the unit normal, turned toward the ray for a voxel without a back side.
bool nanoBackFace(vec3 mean, vec3 dir, out vec3 n) {
    float consistency = length(mean);
    n = consistency > 0.0 ? mean / consistency : -dir;
    if (dot(n, dir) <= 0.0) return false;
    if (consistency >= kNanoOneSidedConsistency) return true;
    n = -n;
    return false;
}

// The first occupied voxel met by origin + t * dir (world units, unit dir) for t in
// [tMin, tMax]: true with the hit distance and the voxel's index. Without surface offsets every
// occupied voxel is solid and the hit is where the ray enters it. With them, a voxel whose
// faces look one way (consistency at least kNanoPlanarConsistency) is its surface plane: the
// ray hits it where it crosses the plane inside the voxel (within the nudge: a surface on the
// voxel's face is crossed where the ray enters), else goes on. Other voxels stay solid (a thin
// wall's two sides, a column, and corners, whose two perpendicular faces give 0.71 and whose
// mean plane would let rays through the corner); their hit is moved onto their plane, kept
// inside the voxel, so shading happens on the surface rather than at the voxel's entry.
bool nanoFirstHit(vec3 origin, vec3 dir, float tMin, float tMax, out float tHit, out ivec3 voxel) {
    pnanovdb_buf_t buf = pnanovdb_buf_t(0u);
    pnanovdb_readaccessor_t acc = nanoAccessor(uNanoNormalGrid);
    pnanovdb_readaccessor_t offsets = nanoAccessor(uNanoOffsetGrid != 0u ? uNanoOffsetGrid : uNanoNormalGrid);
    const float h = uNanoVoxelSize;
    vec3 o = origin / h;
    // 1/0 is +-inf: an axis the ray does not move along never bounds it.
    vec3 inv = 1.0 / dir;
    vec3 lo = vec3(pnanovdb_root_get_bbox_min(buf, acc.root));
    vec3 hi = vec3(pnanovdb_root_get_bbox_max(buf, acc.root)) + 1.0;
    vec3 ta = (lo - o) * inv, tb = (hi - o) * inv;
    vec3 tNear = min(ta, tb), tFar = max(ta, tb);
    float t = max(tMin / h, max(tNear.x, max(tNear.y, tNear.z)));
    float tEnd = min(tMax / h, min(tFar.x, min(tFar.y, tFar.z)));
    // A nudge past each boundary, in voxels: small against a voxel, large against the float
    // spacing of index coordinates below 2^12.
    const float nudge = 1e-3;
    vec3 side = step(vec3(0.0), dir);  // 1 where the ray leaves a box through its upper face
    for (int i = 0; i < kNanoMaxSteps && t <= tEnd; ++i) {
        ivec3 ijk = ivec3(floor(o + t * dir));
        int dim = int(pnanovdb_readaccessor_get_dim(PNANOVDB_GRID_TYPE_VEC3F, buf, acc, ijk));
        // Leave the voxel or empty node holding ijk (aligned to its size).
        vec3 boxLo = vec3(ijk & ivec3(~(dim - 1)));
        vec3 exitT = (boxLo + side * float(dim) - o) * inv;
        float tExit = max(min(exitT.x, min(exitT.y, exitT.z)), t);
        if (dim == 1 && pnanovdb_readaccessor_is_active(PNANOVDB_GRID_TYPE_VEC3F, buf, acc, ijk)) {
            vec3 mean = nanoReadVec3(acc, ijk);
            float consistency = length(mean);
            float tEntry = max(t * h, tMin);
            voxel = ijk;
            if (uNanoOffsetGrid == 0u || !(consistency > 0.0)) {
                tHit = tEntry;
                return true;
            }
            vec3 n = mean / consistency;
            float dn = dot(dir, n);
            vec3 onPlane = (vec3(ijk) + 0.5) * h + nanoReadFloat(offsets, ijk) * n;
            bool crosses = abs(dn) > 1e-6;
            float tPlane = crosses ? dot(onPlane - origin, n) / dn : -1.0;
            if (consistency < kNanoPlanarConsistency) {
                tHit = crosses ? clamp(tPlane, tEntry, max(tEntry, min(tExit * h, tMax))) : tEntry;
                return true;
            }
            if (tPlane >= max((t - 2.0 * nudge) * h, tMin) && tPlane <= min((tExit + 2.0 * nudge) * h, tMax)) {
                tHit = max(tPlane, tMin);
                return true;
            }
        }
        t = tExit + nudge;
    }
    return false;
}

// The occupied voxel nearest to `centre` among those overlapping the world box centre +-
// halfExtent, and the point of it (as a box) nearest to `centre`; with `anyWillDo` the first
// one found. False when the box holds none. Leaf-sized blocks the tree holds no leaf for are
// skipped whole, so the cost follows the occupied leaves the box meets.
bool nanoNearestOccupied(vec3 centre, vec3 halfExtent, bool anyWillDo, out vec3 nearest) {
    pnanovdb_buf_t buf = pnanovdb_buf_t(0u);
    pnanovdb_readaccessor_t acc = nanoAccessor(uNanoNormalGrid);
    const float h = uNanoVoxelSize;
    ivec3 a = max(ivec3(floor((centre - halfExtent) / h)), pnanovdb_root_get_bbox_min(buf, acc.root));
    ivec3 b = min(ivec3(floor((centre + halfExtent) / h)), pnanovdb_root_get_bbox_max(buf, acc.root));
    float best = 1e30;
    nearest = centre;
    for (int bx = a.x & ~7; bx <= b.x; bx += 8)
        for (int by = a.y & ~7; by <= b.y; by += 8)
            for (int bz = a.z & ~7; bz <= b.z; bz += 8) {
                ivec3 block = ivec3(bx, by, bz);
                if (pnanovdb_readaccessor_get_dim(PNANOVDB_GRID_TYPE_VEC3F, buf, acc, block) != 1u) continue;
                ivec3 from = max(block, a), to = min(block + 7, b);
                for (int x = from.x; x <= to.x; ++x)
                    for (int y = from.y; y <= to.y; ++y)
                        for (int z = from.z; z <= to.z; ++z) {
                            ivec3 voxel = ivec3(x, y, z);
                            if (!pnanovdb_readaccessor_is_active(PNANOVDB_GRID_TYPE_VEC3F, buf, acc, voxel)) continue;
                            vec3 q = clamp(centre, vec3(voxel) * h, vec3(voxel + 1) * h);
                            float d = length(q - centre);
                            if (d < best) {
                                best = d;
                                nearest = q;
                                if (anyWillDo) return true;
                            }
                        }
            }
    return best < 1e30;
}
