// The NanoVDB geometry volume on the GPU: one storage buffer and the uniforms of
// shaders/common/nano_geometry.glsl, shared by every kernel that traces it.
#pragma once

#include <cstdint>

#include "gl/program.h"
#include "gl/resources.h"

namespace voxgi {

struct NanoGeometry;

class NanoGeometryGl {
public:
    // Uploads the grids once (immutable storage). Needs a current GL 4.5 context.
    explicit NanoGeometryGl(const NanoGeometry& geometry);

    // Binds the buffer at `binding` (the shader's NANO_GEOMETRY_BINDING) and sets the grid
    // offsets and voxel size on `program`.
    void bind(const gl::Program& program, GLuint binding) const;

private:
    gl::Handle buffer_;
    std::uint32_t normalGrid_ = 0, albedoGrid_ = 0, offsetGrid_ = 0;
    float voxelSize_ = 0.0f;
};

}  // namespace voxgi
