#include "gi/lpv/static_blockers.h"

#include <cstdlib>
#include <filesystem>

namespace voxgi {

void staticBlockers(const SparseGeometryVolume& voxels, int level, BlockerVolume& out) {
    const CascadeGrid& g = out.grid;
    const int n = g.resolution;
    // Voxels whose corners touch the cascade's corner lattice.
    for (int z = -1; z <= n; ++z)
        for (int y = -1; y <= n; ++y)
            for (int x = -1; x <= n; ++x) {
                glm::ivec3 voxel = g.origin + glm::ivec3(x, y, z);
                if (!voxels.occupied(voxel, level)) continue;
                glm::vec4 b = voxels.blockerSH(voxel, level);
                glm::vec3 a = voxels.albedo(voxel, level);
                // The corner plane behind the surface along its normal's dominant axis takes
                // it; the other axes keep both planes. 
                const glm::vec3 m = voxels.normal(voxel, level);
                glm::ivec3 lo(0), hi(1);
                for (int k = 0; k < 3; ++k)
                    if (m[k] != 0.0f) lo[k] = hi[k] = m[k] > 0.0f ? 0 : 1;
                for (int dz = lo.z; dz <= hi.z; ++dz)
                    for (int dy = lo.y; dy <= hi.y; ++dy)
                        for (int dx = lo.x; dx <= hi.x; ++dx) {
                            glm::ivec3 c(x + dx, y + dy, z + dz);
                            if (glm::any(glm::lessThan(c, glm::ivec3(0))) || glm::any(glm::greaterThan(c, glm::ivec3(n))))
                                continue;
                            std::size_t i = out.cornerIndex(c);
                            out.blocker[i] = mergeBlockers(out.blocker[i], b);
                            out.albedo[i] = glm::max(out.albedo[i], a);
                        }
            }
}

std::string geometryCacheDir() {
    namespace fs = std::filesystem;
    fs::path dir;
    if (const char* env = std::getenv("VOXGI_CACHE_DIR"); env && *env) dir = env;
    else if (const char* home = std::getenv("HOME"); home && *home) dir = fs::path(home) / ".cache" / "voxgi";
    else dir = fs::temp_directory_path() / "voxgi-cache";
    std::error_code ec;
    fs::create_directories(dir, ec);
    return dir.string();
}

}  // namespace voxgi
