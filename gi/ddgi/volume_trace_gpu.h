// Rays cast on the GPU through a geometry volume uploaded as NanoVDB (shaders/ddgi/
// volume_rays.comp): the first step of tracing DDGI's probe rays on the GPU. A hit is the
// entry into the first occupied voxel, so it lies up to a voxel diagonal before the surface.
// Or through the scene's triangles (shaders/ddgi/bvh_rays.comp, gi/raytrace/triangle_bvh_gl.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include <memory>

#include "gi/ddgi/nano_geometry_gl.h"
#include "gi/raytrace/triangle_bvh_gl.h"
#include "gl/program.h"
#include "gl/resources.h"

namespace voxgi {

struct NanoGeometry;
struct Scene;
struct TriangleBvh;

// std430 layouts of volume_rays.comp's buffers.
struct VolumeRay {
    glm::vec3 origin{0.0f};
    float tMax = 0.0f;
    glm::vec3 direction{0.0f, 0.0f, 1.0f};  // unit
    float tMin = 0.0f;
};
struct VolumeHit {
    glm::vec3 normal{0.0f};  // unit, facing the ray; zero for misses and back faces
    float distance = 0.0f;   // signed: negative for a back face; the miss distance for a miss
    glm::vec3 albedo{0.0f};
    float triangle = 0.0f;  // through triangles: the hit triangle in leaf order as int bits (-1: none)
};

class VolumeTracerGl {
public:
    // Uploads the grids once; needs a current GL 4.5 context.
    explicit VolumeTracerGl(const NanoGeometry& geometry);
    // The same rays through `bvh`'s triangles.
    VolumeTracerGl(const Scene& scene, const TriangleBvh& bvh);
    ~VolumeTracerGl();

    // Casts `rays` and reads the hits back (misses at `missDistance`).
    std::vector<VolumeHit> trace(const std::vector<VolumeRay>& rays, float missDistance);
    // GPU time of the last trace's kernel (GL_TIME_ELAPSED; llvmpipe reports 0), and the wall
    // time from dispatch to glFinish, both without the transfers.
    double lastKernelMs() const { return kernelMs_; }
    double lastKernelWallMs() const { return kernelWallMs_; }

private:
    gl::Program program_;
    std::unique_ptr<NanoGeometryGl> geometry_;
    std::unique_ptr<TriangleBvhGl> triangles_;
    gl::Handle rays_, hits_, query_;
    std::size_t raysBytes_ = 0;
    double kernelMs_ = 0.0, kernelWallMs_ = 0.0;
};

}  // namespace voxgi
