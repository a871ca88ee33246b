#include "gi/ddgi/ddgi_technique.h"

#include "gi/ddgi/ddgi_debug_views.h"
#include "gi/ddgi/ddgi_gpu.h"
#include "gi/ddgi/occupancy_query.h"
#include "gi/raytrace/ray_tracer.h"
#include "gi/sky/sky_volume_texture.h"
#include "volumes/nano_geometry.h"

namespace voxgi {

DdgiTechnique::DdgiTechnique(const Scene& scene, GeometryQuery query) {
    DdgiDesc desc = readDdgiDesc(scene.gi);
    tracer_ = std::make_unique<RayTracer>(scene);
    if (desc.occupancy && !query.distanceToGeometry && scene.triangleCount() > 0) {
        // The finest volume's cells decide the voxel size; coarser cascades see a finer grid.
        ProbeVolume finest = layoutVolumes(desc, scene.bounds(), scene.camera.eye,
                                           glm::normalize(scene.camera.target - scene.camera.eye)).front();
        GeometryQuery occupancy = occupancyQuery(voxelizeForProbes(scene, finest), finest);
        query.distanceToGeometry = std::move(occupancy.distanceToGeometry);
    }
    system_ = std::make_unique<DdgiSystem>(*tracer_, desc, std::move(query));
    gpu_ = std::make_unique<DdgiGpu>(system_->field());
    if (desc.trace != DdgiTrace::Triangles && scene.triangleCount() > 0)
        gpu_->traceOnGpu(*tracer_, system_->field(), desc.trace);
}

DdgiTechnique::~DdgiTechnique() = default;

void DdgiTechnique::update(const FrameInput& input, const GBufferView& gbuffer) {
    // The frame lights surfaces with the sky (its sky_light pass, or none with sky.light=false):
    // the probes carry only light that bounced, the sky's among it, as the reference's indirect
    // layer does.
    system_->setSky({false, input.sky ? &input.sky->volume() : nullptr});
    gpu_->setSky(false, input.sky);
    BlendBackend* backend = system_->desc().gpuBlend() ? gpu_.get() : nullptr;
    // The GPU update brackets its own stages in the frame's timers (their GPU time, without a
    // wait); the CPU's are timed by the system.
    const bool onGpu = gpu_->updatesProbes();
    gpu_->timeStagesWith(onGpu ? &input.timers : nullptr);
    lastStats_ = system_->update(gbuffer.eye, backend, viewForward(gbuffer.viewProjection));
    gpu_->timeStagesWith(nullptr);
    // The system runs every stage each frame; the plan lists each one (ddgi_method.cpp).
    const std::pair<const char*, double> stages[] = {{kDdgiTraceStage, lastStats_.traceMs},
                                                     {kDdgiShadeStage, lastStats_.shadeMs},
                                                     {kDdgiBlendStage, lastStats_.blendMs},
                                                     {kDdgiBorderStage, lastStats_.borderMs},
                                                     {kDdgiClassifyStage, lastStats_.classifyMs}};
    for (const auto& [stage, ms] : stages)
        if (input.plan.runs(stage) && !(onGpu && stage != kDdgiShadeStage)) input.timers.addCpu(stage, ms);
    if (onGpu) return;  // the GPU relocated and classified: its records are the newest
    if (backend) gpu_->uploadProbeData(system_->field());
    else gpu_->upload(system_->field());
}

void DdgiTechnique::applyIndirect(const FrameInput& input, const GBufferView& gbuffer) {
    if (!input.plan.runs("ddgi.sample")) return;
    input.timers.begin("ddgi.sample");
    gpu_->apply(system_->field(), gbuffer);
    input.timers.end();
}

void DdgiTechnique::dumpVdb(const std::string& path) const {
    gpu_->syncToCpu(system_->field());
    if (!gpu_->updatesProbes()) return writeProbeVdb(system_->field(), path);
    // The volume the GPU traces, built again (it lives only on the GPU).
    const NanoGeometry trace = voxelizeForTracing(*tracer_, system_->field());
    writeProbeVdb(system_->field(), path, &trace);
}

DebugDrawing DdgiTechnique::debugView(const std::string& view, const DebugViewContext& context) const {
    if (view == kCascadeBoundsView) return probeBounds(system_->field());
    if (view == kProbesView) {
        gpu_->syncToCpu(system_->field());
        return probeSpheres(system_->field(), probesOptions().read(context.options).color, context.exposureStops);
    }
    return {};
}

}  // namespace voxgi
