// ddgi.trace = volume or bvh: the blend rays traced and shaded on the GPU (shaders/ddgi/
// volume_shade.comp) through the scene's geometry volume uploaded once as NanoVDB, or through
// its triangles (gi/raytrace/triangle_bvh_gl.h), written into the buffer the blend kernels read, so
// no shaded ray crosses the bus. The Embree trace and CPU shading (gi/ddgi/probe_rays.h,
// hit_shading.h) are its reference. The volume also classifies the probes (classify.comp).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <memory>

#include "gi/ddgi/nano_geometry_gl.h"
#include "gi/raytrace/triangle_bvh_gl.h"
#include "gi/ddgi/probe_blend.h"
#include "shaders/shared/light_model.h"
#include "gl/program.h"
#include "gl/resources.h"

namespace voxgi {

struct NanoGeometry;
struct Scene;
class SkyVolumeTexture;
struct TriangleBvh;

class VolumeShadeGl {
public:
    // Uploads the grids (and the triangles when `triangles` is given: the rays trace them);
    // `scene` (its lights and sky) must outlive this. Needs a GL 4.5 context.
    VolumeShadeGl(const NanoGeometry& geometry, const Scene& scene, const TriangleBvh* triangles = nullptr);

    // Per frame, before dispatch(): this frame's quad-light points (as uniforms) and the
    // scene's lights (uploaded when they change).
    void prepare(const RaySet& rays, std::uint32_t frame);
    // Where the rays find the sky (hit_shading.h's ProbeSky; `volume` is its GPU copy, bound
    // while it lives).
    void setSky(bool atMisses, const SkyVolumeTexture* volume) {
        skyAtMisses_ = atMisses;
        skyVolume_ = volume;
    }
    // Shades every job's blend rays into the ray buffer bound at 2, with the jobs bound at 0,
    // the unrotated blend directions at 1 (turned by rays.rotation) and the jobs' probe
    // positions in `origins`; reads the previous
    // field from the atlases and probe data. The job count is the y of the indirect dispatch at
    // `indirectOffset` in the buffer bound to GL_DISPATCH_INDIRECT_BUFFER.
    void dispatch(const ProbeField& field, const RaySet& rays, GLuint origins, GLintptr indirectOffset,
                  GLuint irradiance, GLuint distance, GLuint probeData);
    const NanoGeometryGl& geometry() const { return geometry_; }
    const TriangleBvhGl* triangles() const { return triangles_.get(); }  // null: the rays trace the volume

private:
    const Scene& scene_;
    gl::Program program_;
    NanoGeometryGl geometry_;
    std::unique_ptr<TriangleBvhGl> triangles_;
    float shadowOffset_ = 0.0f;
    gl::Handle lights_, sky_;
    static constexpr GLuint kSkyTextureUnit = 6;  // 4 and 5: the probe atlases (bindProbeField)
    static constexpr int kSkyVolumeUnit = 7;      // and 8: its brick index
    bool skyAtMisses_ = true;
    const SkyVolumeTexture* skyVolume_ = nullptr;
    std::size_t lightsBytes_ = 0;
    std::array<glm::vec2, kQuadSampleSets> quadStarts_{};  // quadSampleStart, this frame
    std::vector<shading::PackedLight> uploadedLights_;  // what lights_ holds
    int lightCount_ = 0;
    bool quadLights_ = false;
};

// The defines of the kernels that trace the volume or, with `triangles`, the triangles' BVH.
gl::Program::Defines traceDefines(bool triangles);

// The probe field's uniforms of shaders/ddgi/sampling.glsl (volumes, atlases on texture units
// 4 and 5, probe data at storage binding 5), for every pass that samples the field.
void bindProbeField(const gl::Program& program, const ProbeField& field, GLuint irradiance, GLuint distance,
                    GLuint probeData);

}  // namespace voxgi
