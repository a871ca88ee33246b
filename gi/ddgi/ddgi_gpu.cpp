#include "gi/ddgi/ddgi_gpu.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>

#include "gi/ddgi/occupancy_query.h"
#include "gi/raytrace/ray_tracer.h"
#include "gi/raytrace/triangle_bvh.h"
#include "gl/context.h"
#include "gl/readback_ring.h"
#include "gl/timers.h"
#include "gl/screen_pass.h"
#include "gi/sampling/sequences.h"
#include "shaders/ddgi/limits.h"
#include "shaders/shared/probe_schedule.h"
#include "volumes/nano_geometry.h"

namespace voxgi {

namespace {
gl::Handle makeAtlasTexture(const Atlas& atlas) {
    gl::Handle t = gl::createTexture(GL_TEXTURE_2D, GL_RGBA32F, atlas.width, atlas.height);
    glTextureParameteri(t.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(t.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    return t;
}

// `rows`: staging memory kept between frames (a fresh 10 MB buffer costs its page faults).
void uploadAtlas(GLuint texture, const Atlas& atlas, std::vector<glm::vec4>& rows) {
    atlas.toRows(rows);
    glTextureSubImage2D(texture, 0, 0, 0, atlas.width, atlas.height, GL_RGBA, GL_FLOAT, rows.data());
}

void downloadAtlas(GLuint texture, Atlas& atlas, std::vector<glm::vec4>& rows) {
    rows.resize(atlas.texels.size());
    glGetTextureImage(texture, 0, GL_RGBA, GL_FLOAT, GLsizei(rows.size() * sizeof(glm::vec4)), rows.data());
    atlas.fromRows(rows);
}

std::string indexed(const char* name, int i) { return std::string(name) + "[" + std::to_string(i) + "]"; }

// Workgroups (8x8) per tile side of blend.comp (the interior texels) and border.comp (the tile).
GLuint blendGroups(int texels) { return GLuint((texels + 7) / 8); }
GLuint borderGroups(int texels) { return GLuint((texels + 2 + 7) / 8); }

// One pass over the tiles of `jobs` jobs, or of the job count in indirect dispatch `dispatch`
// (jobs < 0: the GPU's own schedule).
void dispatchTiles(GLuint groups, int jobs, int dispatch) {
    if (jobs >= 0) glDispatchCompute(groups, groups, GLuint(jobs));
    else glDispatchComputeIndirect(GLintptr(3 * dispatch * sizeof(GLuint)));
}

// What the passes that wrote the atlases wrote, for the passes and transfers after them.
void atlasBarrier() {
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
}

// Ends a timed pass and waits for it: its GPU time.
double endTimedPass(GLuint query) {
    glEndQuery(GL_TIME_ELAPSED);
    glFinish();
    return gl::timerQueryMs(query);
}

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

// What updateProbes reads back: the counters, then the shade dispatch's job count.
constexpr std::size_t kCountsBytes = (shading::kDdgiCounters + 1) * sizeof(GLuint);
}  // namespace

DdgiGpu::DdgiGpu(const ProbeField& field) {
    if (field.volumes().size() > std::size_t(kDdgiMaxVolumes))
        throw gl::GlError("DDGI: at most " + std::to_string(kDdgiMaxVolumes) + " cascades on the GPU");
    blendIrradiance_ = gl::Program::compute("ddgi/blend.comp", {{"DISTANCE", "0"}});
    // The field's exponent as a constant of the program (its settings are fixed for its life).
    char exponent[48];
    std::snprintf(exponent, sizeof(exponent), "float(%.9g)", double(BlendParams::from(field.desc()).distanceExponent));
    blendDistance_ = gl::Program::compute("ddgi/blend.comp", {{"DISTANCE", "1"}, {"DISTANCE_EXPONENT", exponent}});
    border_ = gl::Program::compute("ddgi/border.comp");
    apply_ = gl::Program::compute("ddgi/apply.comp");
    irradiance_ = makeAtlasTexture(field.irradiance);
    distance_ = makeAtlasTexture(field.distance);
    blendQuery_ = gl::createTimerQuery();
    borderQuery_ = gl::createTimerQuery();
    shadeQuery_ = gl::createTimerQuery();
    classifyQuery_ = gl::createTimerQuery();
    upload(field);
}

DdgiGpu::~DdgiGpu() = default;

void DdgiGpu::traceInVolume(const NanoGeometry& geometry, const Scene& scene, const TriangleBvh* triangles) {
    volume_ = std::make_unique<VolumeShadeGl>(geometry, scene, triangles);
    schedule_ = gl::Program::compute("ddgi/schedule.comp");
    classify_ = gl::Program::compute("ddgi/classify.comp", traceDefines(triangles != nullptr));
    dispatches_ = gl::createBuffer(3 * shading::kDdgiDispatches * sizeof(GLuint));
    counters_ = gl::createBuffer(shading::kDdgiCounters * sizeof(GLuint));
    counts_ = std::make_unique<gl::ReadbackRing>(kCountsBytes);
}

void DdgiGpu::traceOnGpu(const RayTracer& tracer, const ProbeField& field, DdgiTrace trace) {
    const TriangleBvh bvh = trace == DdgiTrace::Bvh ? buildTriangleBvh(tracer.scene()) : TriangleBvh{};
    traceInVolume(voxelizeForTracing(tracer, field), tracer.scene(), trace == DdgiTrace::Bvh ? &bvh : nullptr);
}

void DdgiGpu::upload(const ProbeField& field) {
    uploadAtlases(field);
    uploadProbeData(field);
}

void DdgiGpu::uploadAtlases(const ProbeField& field) {
    uploadAtlas(irradiance_.id(), field.irradiance, staging_);
    uploadAtlas(distance_.id(), field.distance, staging_);
    synced_ = &field;
    syncedVersion_ = field.atlasVersion();
}

std::vector<glm::vec4> DdgiGpu::readRayValues(std::size_t count) const {
    std::vector<glm::vec4> values(std::min(count, raysBytes_ / sizeof(glm::vec4)));
    if (!values.empty())
        glGetNamedBufferSubData(rays_.id(), 0, GLsizeiptr(values.size() * sizeof(glm::vec4)), values.data());
    return values;
}

void DdgiGpu::uploadProbeData(const ProbeField& field) {
    std::vector<glm::vec4> data;
    data.reserve(field.probes.size());
    for (const ProbeRecord& r : field.probes) data.emplace_back(r.offset, float(int(r.state)));
    gl::ensureBuffer(probeData_, probeDataBytes_, data.size() * sizeof(glm::vec4));
    glNamedBufferSubData(probeData_.id(), 0, GLsizeiptr(data.size() * sizeof(glm::vec4)), data.data());
    if (!volume_) return;
    std::vector<GLint> blends;
    blends.reserve(field.probes.size());
    for (const ProbeRecord& r : field.probes) blends.push_back(r.blends);
    gl::ensureBuffer(blends_, blendsBytes_, blends.size() * sizeof(GLint));
    glNamedBufferSubData(blends_.id(), 0, GLsizeiptr(blends.size() * sizeof(GLint)), blends.data());
}

std::vector<BlendJob> DdgiGpu::readJobs(std::size_t count) const {
    std::vector<BlendJob> jobs(std::min(count, jobsBytes_ / sizeof(BlendJob)));
    if (!jobs.empty())
        glGetNamedBufferSubData(jobs_.id(), 0, GLsizeiptr(jobs.size() * sizeof(BlendJob)), jobs.data());
    return jobs;
}

void DdgiGpu::readBack(ProbeField& field) {
    downloadAtlas(irradiance_.id(), field.irradiance, staging_);
    downloadAtlas(distance_.id(), field.distance, staging_);
    if (volume_) {  // the records too: the GPU relocates and classifies
        const std::size_t n = field.probes.size();
        std::vector<glm::vec4> data(n);
        std::vector<GLint> blends(n);
        glGetNamedBufferSubData(probeData_.id(), 0, GLsizeiptr(n * sizeof(glm::vec4)), data.data());
        glGetNamedBufferSubData(blends_.id(), 0, GLsizeiptr(n * sizeof(GLint)), blends.data());
        for (std::size_t p = 0; p < n; ++p) {
            field.probes[p].offset = glm::vec3(data[p]);
            field.probes[p].state = ProbeState(int(data[p].w));
            field.probes[p].blends = blends[p];
        }
    }
    synced_ = &field;  // the CPU copy is the GPU's again
    syncedVersion_ = field.atlasVersion();
}

void DdgiGpu::blend(ProbeField& field, const RaySet& rays, const ShadedRays& shaded,
                    const std::vector<BlendJob>& jobs) {
    times_ = Times{};
    const auto start = std::chrono::steady_clock::now();
    // Only when the CPU wrote to the atlases (probe resets when scrolling) since the GPU copy
    // was made: on real hardware the upload took 7 times as long as the kernels.
    if (synced_ != &field || syncedVersion_ != field.atlasVersion()) {
        uploadAtlases(field);
        times_.atlasesUploaded = true;
    }
    if (jobs.empty()) return;
    uploadDirections(rays);
    gl::ensureBuffer(jobs_, jobsBytes_, jobs.size() * sizeof(BlendJob));
    gl::ensureBuffer(rays_, raysBytes_, shaded.values.size() * sizeof(glm::vec4));
    glNamedBufferSubData(jobs_.id(), 0, GLsizeiptr(jobs.size() * sizeof(BlendJob)), jobs.data());
    glNamedBufferSubData(rays_.id(), 0, GLsizeiptr(shaded.values.size() * sizeof(glm::vec4)), shaded.values.data());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, jobs_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, directions_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, rays_.id());
    glFinish();  // the transfers end here, so the kernels' timing holds only the kernels
    times_.uploadMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    glBeginQuery(GL_TIME_ELAPSED, blendQuery_.id());
    blendKernels(field, rays, int(jobs.size()));
    times_.blendGpuMs = endTimedPass(blendQuery_.id());
}

void DdgiGpu::uploadDirections(const RaySet& rays) {
    // The unrotated directions, once: the kernels rotate them by the frame's rotation (a uniform).
    if (rays.blendRays == blendDirectionCount_ && rays.fixedRays == fixedDirectionCount_) return;
    std::vector<glm::vec4> blend, fixed;
    for (int i = 0; i < rays.blendRays; ++i) blend.emplace_back(sphericalFibonacci(i, rays.blendRays), 0.0f);
    for (int i = 0; i < rays.fixedRays; ++i) fixed.emplace_back(rays.directions[std::size_t(i)], 0.0f);
    fixed.resize(std::max<std::size_t>(fixed.size(), 1));
    directions_ = gl::createBuffer(blend.size() * sizeof(glm::vec4), blend.data());
    fixedDirections_ = gl::createBuffer(fixed.size() * sizeof(glm::vec4), fixed.data());
    blendDirectionCount_ = rays.blendRays;
    fixedDirectionCount_ = rays.fixedRays;
}

void DdgiGpu::blendKernels(const ProbeField& field, const RaySet& rays, int jobs) {
    const BlendParams bp = BlendParams::from(field.desc());
    auto run = [&](gl::Program& program, GLuint atlas, int texels, int dispatch) {
        program.use();
        program.set("uTexels", texels);
        program.set("uRays", rays.blendRays);
        program.set("uRayRotation", rays.rotation);
        program.set("uGamma", bp.irradianceGamma);
        program.set("uIrradianceThreshold", bp.irradianceThreshold);
        program.set("uBrightnessThreshold", bp.brightnessThreshold);
        program.set("uBackfaceScale", kBackfaceDistanceScale);
        glBindImageTexture(0, atlas, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
        dispatchTiles(blendGroups(texels), jobs, dispatch);
    };
    run(blendIrradiance_, irradiance_.id(), bp.irradianceTexels, shading::kDdgiDispatchBlendIrradiance);
    run(blendDistance_, distance_.id(), bp.distanceTexels, shading::kDdgiDispatchBlendDistance);
    atlasBarrier();
}

void DdgiGpu::border(ProbeField& field, const std::vector<BlendJob>& jobs) {
    if (!jobs.empty()) {
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, jobs_.id());
        glBeginQuery(GL_TIME_ELAPSED, borderQuery_.id());
        borderKernels(field, int(jobs.size()));
        times_.borderGpuMs = endTimedPass(borderQuery_.id());
    }
    const auto start = std::chrono::steady_clock::now();
    readBack(field);
    times_.readbackMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

void DdgiGpu::borderKernels(const ProbeField& field, int jobs) {
    border_.use();
    auto run = [&](GLuint atlas, int texels, int isDistance, int dispatch) {
        border_.set("uTexels", texels);
        border_.set("uDistance", isDistance);
        glBindImageTexture(0, atlas, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
        dispatchTiles(borderGroups(texels), jobs, dispatch);
    };
    run(irradiance_.id(), field.desc().irradianceTexels, 0, shading::kDdgiDispatchBorderIrradiance);
    run(distance_.id(), field.desc().distanceTexels, 1, shading::kDdgiDispatchBorderDistance);
    atlasBarrier();
}

std::chrono::steady_clock::time_point DdgiGpu::beginStage(const char* stage, GLuint query) {
    if (waitForEachStage_) glBeginQuery(GL_TIME_ELAPSED, query);
    else if (stageTimers_) stageTimers_->begin(stage);
    return Clock::now();
}

double DdgiGpu::endStage(GLuint query, std::chrono::steady_clock::time_point start, double& gpuMs) {
    if (waitForEachStage_) {
        gpuMs = endTimedPass(query);
    } else if (stageTimers_) {
        stageTimers_->end();
    }
    return msSince(start);
}

BlendBackend::UpdateReport DdgiGpu::updateProbes(ProbeField& field, const RaySet& rays, std::uint32_t frame) {
    times_ = Times{};
    UpdateReport report;
    const DdgiDesc& desc = field.desc();
    const std::size_t probes = field.probes.size();
    if (synced_ != &field || syncedVersion_ != field.atlasVersion() || blendsBytes_ < probes * sizeof(GLint)) {
        // A scroll reset probes on the CPU (it read everything back first): both go up.
        uploadAtlases(field);
        uploadProbeData(field);
        times_.atlasesUploaded = true;
    }
    // Per frame nothing goes up but uniforms: the directions went up once, the lights go up
    // when they change (VolumeShadeGl::prepare), and the dispatches' job counts and the
    // counters are cleared on the GPU.
    uploadDirections(rays);
    if (dispatchRays_ != rays.blendRays) {  // the dispatches' fixed sizes; their job counts are cleared below
        const GLuint bi = blendGroups(desc.irradianceTexels), bd = blendGroups(desc.distanceTexels);
        const GLuint ri = borderGroups(desc.irradianceTexels), rd = borderGroups(desc.distanceTexels);
        const GLuint dispatches[3 * shading::kDdgiDispatches] = {
            GLuint((rays.blendRays + 63) / 64), 0, 1, bi, bi, 0, bd, bd, 0, ri, ri, 0, rd, rd, 0};
        glNamedBufferSubData(dispatches_.id(), 0, sizeof(dispatches), dispatches);
        dispatchRays_ = rays.blendRays;
    }
    const GLuint zero = 0;
    for (int d = 0; d < shading::kDdgiDispatches; ++d)
        glClearNamedBufferSubData(dispatches_.id(), GL_R32UI,
                                  GLintptr((3 * d + (d == shading::kDdgiDispatchShade ? 1 : 2)) * sizeof(GLuint)),
                                  sizeof(GLuint), GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    glClearNamedBufferData(counters_.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    gl::ensureBuffer(jobs_, jobsBytes_, probes * sizeof(BlendJob));
    gl::ensureBuffer(rays_, raysBytes_, probes * std::size_t(rays.blendRays) * sizeof(glm::vec4));
    gl::ensureBuffer(origins_, originsBytes_, probes * sizeof(glm::vec4));
    gl::ensureBuffer(works_, worksBytes_, probes * sizeof(GLint));
    volume_->prepare(rays, frame);

    // Each stage's barrier orders the next; nothing waits for the GPU unless asked
    // (waitForEachStage), and what the update counted comes back frames later (counts_).
    const GLuint probeGroups = GLuint((probes + 63) / 64);
    auto bindUpdate = [&](const gl::Program& program) {
        bindProbeField(program, field, irradiance_.id(), distance_.id(), probeData_.id());
        program.set("uProbeCount", int(probes));
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 9, blends_.id());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 10, works_.id());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 11, counters_.id());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 12, dispatches_.id());
    };
    double scheduleGpuMs = 0.0;
    auto start = beginStage(kDdgiClassifyStage, classifyQuery_.id());
    schedule_.use();
    bindUpdate(schedule_);
    schedule_.set("uFrame", int(frame));
    schedule_.set("uRays", rays.blendRays);
    schedule_.set("uClassify", desc.classify ? 1 : 0);
    schedule_.set("uSleepInterval", desc.sleepInterval);
    schedule_.set("uHysteresis", desc.hysteresis);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, jobs_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, origins_.id());
    glDispatchCompute(probeGroups, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
    report.classifyMs = endStage(classifyQuery_.id(), start, scheduleGpuMs);

    start = beginStage(kDdgiTraceStage, shadeQuery_.id());
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, dispatches_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, jobs_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, directions_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, rays_.id());
    // Reads the previous field before the blend below overwrites it.
    volume_->dispatch(field, rays, origins_.id(), GLintptr(3 * shading::kDdgiDispatchShade * sizeof(GLuint)),
                      irradiance_.id(), distance_.id(), probeData_.id());
    report.traceMs = endStage(shadeQuery_.id(), start, times_.shadeGpuMs);

    start = beginStage(kDdgiBlendStage, blendQuery_.id());
    blendKernels(field, rays, -1);
    report.blendMs = endStage(blendQuery_.id(), start, times_.blendGpuMs);
    start = beginStage(kDdgiBorderStage, borderQuery_.id());
    borderKernels(field, -1);
    report.borderMs = endStage(borderQuery_.id(), start, times_.borderGpuMs);

    start = beginStage(kDdgiClassifyStage, classifyQuery_.id());
    classify_.use();
    bindUpdate(classify_);
    volume_->geometry().bind(classify_, 3);
    if (volume_->triangles()) volume_->triangles()->bind(classify_, 14);
    classify_.set("uFixedRays", rays.fixedRays);
    classify_.set("uClassify", desc.classify ? 1 : 0);
    classify_.set("uRelocate", desc.relocate ? 1 : 0);
    classify_.set("uMissDistance", kMissDistance);
    classify_.set("uBackfaceThreshold", desc.backfaceThreshold);
    classify_.set("uRelocationBackfaceThreshold", desc.relocationBackfaceThreshold);
    classify_.set("uMinFrontfaceDistance", desc.minFrontfaceDistance);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 13, fixedDirections_.id());
    glDispatchCompute(probeGroups, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    // What the update counted, 20 bytes, copied on the GPU for a later frame to read.
    counts_->push(frame, {{counters_.id(), 0, shading::kDdgiCounters * sizeof(GLuint)},
                          {dispatches_.id(), (3 * shading::kDdgiDispatchShade + 1) * sizeof(GLuint), sizeof(GLuint)}});
    report.classifyMs += endStage(classifyQuery_.id(), start, times_.classifyGpuMs);
    times_.classifyGpuMs += scheduleGpuMs;

    GLuint counts[shading::kDdgiCounters + 1];
    std::uint64_t countedFrame = 0;
    if (waitForEachStage_ ? counts_->finish(countedFrame, counts) : counts_->latest(countedFrame, counts)) {
        lastCounts_.blended = int(counts[shading::kDdgiCounters]);
        lastCounts_.fixedOnly = int(counts[shading::kDdgiCountFixedOnly]);
        lastCounts_.active = int(counts[shading::kDdgiCountStates + shading::kProbeActive]);
        lastCounts_.sleeping = int(counts[shading::kDdgiCountStates + shading::kProbeSleeping]);
        lastCounts_.off = int(counts[shading::kDdgiCountStates + shading::kProbeOff]);
        lastCounts_.countedFrame = std::int64_t(countedFrame);
    }
    // The newest counts that came back, with this update's times.
    UpdateReport out = lastCounts_;
    out.traceMs = report.traceMs;
    out.blendMs = report.blendMs;
    out.borderMs = report.borderMs;
    out.classifyMs = report.classifyMs;
    cpuStale_ = true;
    return out;
}

void DdgiGpu::syncToCpu(ProbeField& field) {
    if (!cpuStale_) return;
    readBack(field);
    cpuStale_ = false;
}

void bindProbeField(const gl::Program& program, const ProbeField& field, GLuint irradiance, GLuint distance,
                    GLuint probeData) {
    const DdgiDesc& desc = field.desc();
    glBindTextureUnit(4, irradiance);
    glBindTextureUnit(5, distance);
    program.set("uIrradianceAtlas", 4);
    program.set("uDistanceAtlas", 5);
    program.set("uVolumeCount", int(field.volumes().size()));
    for (int v = 0; v < int(field.volumes().size()); ++v) {
        const ProbeVolume& vol = field.volumes()[std::size_t(v)];
        program.set(indexed("uCounts", v).c_str(), vol.counts);
        program.set(indexed("uSpacing", v).c_str(), vol.spacing);
        program.set(indexed("uOrigin", v).c_str(), vol.origin);
        program.set(indexed("uScroll", v).c_str(), vol.scroll);
        program.set(indexed("uProbeBase", v).c_str(), vol.probeBase);
        program.set(indexed("uTileRow", v).c_str(), vol.tileRow);
    }
    program.set("uIrradianceTexels", desc.irradianceTexels);
    program.set("uDistanceTexels", desc.distanceTexels);
    program.set("uNormalBias", desc.normalBias);
    program.set("uViewBias", desc.viewBias);
    program.set("uGamma", desc.irradianceGamma);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, probeData);
}

void DdgiGpu::apply(const ProbeField& field, const GBufferView& g) {
    apply_.use();
    glBindTextureUnit(0, g.position);
    glBindTextureUnit(1, g.normal);
    glBindTextureUnit(2, g.albedo);
    glBindTextureUnit(3, g.emission);
    apply_.set("uPosition", 0);
    apply_.set("uNormal", 1);
    apply_.set("uAlbedo", 2);
    apply_.set("uEmission", 3);
    apply_.set("uEye", g.eye);
    bindProbeField(apply_, field, irradiance_.id(), distance_.id(), probeData_.id());
    gl::addToBoundTarget(apply_);
}

}  // namespace voxgi
