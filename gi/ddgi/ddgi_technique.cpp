#include "gi/ddgi/ddgi_technique.h"

#include "gi/ddgi/ddgi_gpu.h"
#include "gi/ddgi/occupancy_query.h"
#include "gi/raytrace/ray_tracer.h"

namespace voxgi {

DdgiTechnique::DdgiTechnique(const Scene& scene, GeometryQuery query) {
    DdgiDesc desc = readDdgiDesc(scene.gi);
    tracer_ = std::make_unique<RayTracer>(scene);
    if (desc.occupancy && !query.distanceToGeometry && scene.triangleCount() > 0) {
        // The finest volume's cells decide the voxel size; coarser cascades see a finer grid.
        ProbeVolume finest = layoutVolumes(desc, scene.bounds(), scene.camera.eye).front();
        GeometryQuery occupancy = occupancyQuery(voxelizeForProbes(scene, finest), finest);
        query.distanceToGeometry = std::move(occupancy.distanceToGeometry);
    }
    system_ = std::make_unique<DdgiSystem>(*tracer_, desc, std::move(query));
    gpu_ = std::make_unique<DdgiGpu>(system_->field());
}

DdgiTechnique::~DdgiTechnique() = default;

void DdgiTechnique::update(const FrameInput& input, const GBufferView& gbuffer) {
    BlendBackend* backend = system_->desc().gpuBlend ? gpu_.get() : nullptr;
    lastStats_ = system_->update(gbuffer.eye, backend);
    input.timers.addCpu("ddgi.trace", lastStats_.traceMs);
    input.timers.addCpu("ddgi.shade", lastStats_.shadeMs);
    input.timers.addCpu("ddgi.blend", lastStats_.blendMs);
    input.timers.addCpu("ddgi.border", lastStats_.borderMs);
    input.timers.addCpu("ddgi.classify", lastStats_.classifyMs);
    if (backend) gpu_->uploadProbeData(system_->field());
    else gpu_->upload(system_->field());
}

void DdgiTechnique::applyIndirect(const FrameInput& input, const GBufferView& gbuffer) {
    input.timers.begin("ddgi.sample");
    gpu_->apply(system_->field(), gbuffer);
    input.timers.end();
}

void DdgiTechnique::dumpVdb(const std::string& path) const { writeProbeVdb(system_->field(), path); }

std::unique_ptr<GiTechnique> createDdgiTechnique(const Scene& scene) {
    return std::make_unique<DdgiTechnique>(scene);
}

}  // namespace voxgi
