#include "gi/ddgi/volume_shade_gpu.h"

#include <cstring>
#include <string>

#include "gi/ddgi/hit_shading.h"
#include "gi/raytrace/ray_tracer.h"
#include "gi/sampling/sequences.h"
#include "gi/sky/sky_volume_texture.h"
#include "gl/scene_gpu.h"
#include "scenes/scene.h"
#include "shaders/shared/light_model.h"

namespace voxgi {

namespace {
void upload(gl::Handle& buffer, std::size_t& capacity, const void* data, std::size_t bytes) {
    gl::ensureBuffer(buffer, capacity, bytes);
    if (bytes > 0) glNamedBufferSubData(buffer.id(), 0, GLsizeiptr(bytes), data);
}
}  // namespace

gl::Program::Defines traceDefines(bool triangles) {
    if (!triangles) return {};
    return {{"DDGI_TRACE_TRIANGLES", "1"}};
}

VolumeShadeGl::VolumeShadeGl(const NanoGeometry& geometry, const Scene& scene, const TriangleBvh* triangles)
    : scene_(scene),
      program_(gl::Program::compute("ddgi/volume_shade.comp", traceDefines(triangles != nullptr))),
      geometry_(geometry),
      triangles_(triangles ? std::make_unique<TriangleBvhGl>(scene, *triangles) : nullptr),
      shadowOffset_(surfaceRayOffset(scene)),
      sky_(uploadSkyTexture(scene.sky)) {}

void VolumeShadeGl::prepare(const RaySet& rays, std::uint32_t frame) {
    // Lights may move between frames (the viewer drags them): up only when they changed.
    std::vector<shading::PackedLight> lights;
    for (const Light& l : scene_.lights) lights.push_back(shading::packLight(l));
    lightCount_ = int(lights.size());
    const std::size_t bytes = lights.size() * sizeof(shading::PackedLight);
    if (lights.size() != uploadedLights_.size() || (bytes > 0 && std::memcmp(lights.data(), uploadedLights_.data(), bytes) != 0)) {
        upload(lights_, lightsBytes_, lights.data(), bytes);
        uploadedLights_ = std::move(lights);
    }
    quadLights_ = hasQuadLights(scene_);
    // The quad-light points of quadLightSamples, from each row's first point (uniforms).
    for (int residue = 0; residue < kQuadSampleSets; ++residue)
        quadStarts_[std::size_t(residue)] = quadSampleStart(residue, rays.blendRays, frame);
}

void VolumeShadeGl::dispatch(const ProbeField& field, const RaySet& rays, GLuint origins, GLintptr indirectOffset,
                             GLuint irradiance, GLuint distance, GLuint probeData) {
    program_.use();
    bindProbeField(program_, field, irradiance, distance, probeData);
    if (triangles_) {
        triangles_->bind(program_, 3);
        program_.set("uShadowOffset", shadowOffset_);
    } else {
        geometry_.bind(program_, 3);
    }
    program_.set("uRays", rays.blendRays);
    program_.set("uRayRotation", rays.rotation);
    program_.set("uLightCount", lightCount_);
    program_.set("uQuadSampleSets", quadLights_ ? kQuadSampleSets : 0);
    for (int residue = 0; residue < kQuadSampleSets; ++residue)
        program_.set(("uQuadStart[" + std::to_string(residue) + "]").c_str(), quadStarts_[std::size_t(residue)]);
    program_.set("uR2Step", glm::vec2(r2Step()));
    program_.set("uMissDistance", kMissDistance);
    program_.set("uEnergy", field.desc().energyPreservation);
    glBindTextureUnit(kSkyTextureUnit, sky_.id());
    program_.set("uSkyTable", int(kSkyTextureUnit));
    program_.set("uSkyAtMisses", skyAtMisses_ ? 1 : 0);
    program_.set("uSkyVolumeLit", skyVolume_ ? 1 : 0);
    if (skyVolume_) {
        skyVolume_->bind(program_, kSkyVolumeUnit);
    } else {  // unused, but samplers of different types may not share a unit
        program_.set("uSkyVolume", kSkyVolumeUnit);
        program_.set("uSkyBricks", kSkyVolumeUnit + 1);
    }
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, origins);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 6, lights_.id());
    glDispatchComputeIndirect(indirectOffset);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

}  // namespace voxgi
