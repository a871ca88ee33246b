#include "gi/ddgi/volume_trace_gpu.h"

#include <chrono>


namespace voxgi {

static_assert(sizeof(VolumeRay) == 32 && sizeof(VolumeHit) == 32, "std430 layouts of volume_rays.comp");

VolumeTracerGl::VolumeTracerGl(const NanoGeometry& geometry)
    : program_(gl::Program::compute("ddgi/volume_rays.comp")),
      geometry_(std::make_unique<NanoGeometryGl>(geometry)),
      query_(gl::createTimerQuery()) {}

VolumeTracerGl::VolumeTracerGl(const Scene& scene, const TriangleBvh& bvh)
    : program_(gl::Program::compute("ddgi/bvh_rays.comp")),
      triangles_(std::make_unique<TriangleBvhGl>(scene, bvh)),
      query_(gl::createTimerQuery()) {}

VolumeTracerGl::~VolumeTracerGl() = default;

std::vector<VolumeHit> VolumeTracerGl::trace(const std::vector<VolumeRay>& rays, float missDistance) {
    std::vector<VolumeHit> hits(rays.size());
    if (rays.empty()) return hits;
    const std::size_t bytes = rays.size() * sizeof(VolumeRay);
    if (raysBytes_ < bytes) {
        rays_ = gl::createBuffer(bytes);
        hits_ = gl::createBuffer(bytes);
        raysBytes_ = bytes;
    }
    glNamedBufferSubData(rays_.id(), 0, GLsizeiptr(bytes), rays.data());
    program_.use();
    if (geometry_) geometry_->bind(program_, 0);
    else triangles_->bind(program_, 0);
    program_.set("uRayCount", int(rays.size()));
    program_.set("uMissDistance", missDistance);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, rays_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, hits_.id());
    glFinish();
    const auto start = std::chrono::steady_clock::now();
    glBeginQuery(GL_TIME_ELAPSED, query_.id());
    glDispatchCompute(GLuint((rays.size() + 63) / 64), 1, 1);
    glEndQuery(GL_TIME_ELAPSED);
    glFinish();
    kernelWallMs_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(hits_.id(), 0, GLsizeiptr(bytes), hits.data());
    kernelMs_ = gl::timerQueryMs(query_.id());
    return hits;
}

}  // namespace voxgi
