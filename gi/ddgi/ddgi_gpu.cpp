#include "gi/ddgi/ddgi_gpu.h"

#include <chrono>
#include <cstdio>
#include <string>

#include "gl/context.h"
#include "gl/screen_pass.h"
#include "shaders/ddgi/limits.h"

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
    upload(field);
}

DdgiGpu::~DdgiGpu() = default;

void DdgiGpu::traceInVolume(const NanoGeometry& geometry, const Scene& scene) {
    volume_ = std::make_unique<VolumeShadeGl>(geometry, scene);
}

void DdgiGpu::shadeRays(const RaySet& rays, const ProbeTrace& trace, const std::vector<BlendJob>& jobs,
                        std::uint32_t frame) {
    volume_->prepare(rays, trace, jobs, frame);
    shadePending_ = true;
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
}

void DdgiGpu::readBack(ProbeField& field) {
    downloadAtlas(irradiance_.id(), field.irradiance, staging_);
    downloadAtlas(distance_.id(), field.distance, staging_);
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
    if (jobs.empty()) {
        shadePending_ = false;
        return;
    }
    std::vector<glm::vec4> dirs;
    dirs.reserve(std::size_t(rays.blendRays));
    for (int i = 0; i < rays.blendRays; ++i) dirs.emplace_back(rays.blendDirection(i), 0.0f);
    gl::ensureBuffer(jobs_, jobsBytes_, jobs.size() * sizeof(BlendJob));
    gl::ensureBuffer(directions_, directionsBytes_, dirs.size() * sizeof(glm::vec4));
    const bool shadeHere = volume_ && shadePending_;
    shadePending_ = false;
    const std::size_t rayCount = shadeHere ? jobs.size() * std::size_t(rays.blendRays) : shaded.values.size();
    gl::ensureBuffer(rays_, raysBytes_, rayCount * sizeof(glm::vec4));
    glNamedBufferSubData(jobs_.id(), 0, GLsizeiptr(jobs.size() * sizeof(BlendJob)), jobs.data());
    glNamedBufferSubData(directions_.id(), 0, GLsizeiptr(dirs.size() * sizeof(glm::vec4)), dirs.data());
    if (!shadeHere)
        glNamedBufferSubData(rays_.id(), 0, GLsizeiptr(shaded.values.size() * sizeof(glm::vec4)), shaded.values.data());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, jobs_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, directions_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, rays_.id());
    glFinish();  // the transfers end here, so the kernels' timing holds only the kernels
    times_.uploadMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    if (shadeHere) {
        // Reads the previous field before the blend below overwrites it.
        glBeginQuery(GL_TIME_ELAPSED, shadeQuery_.id());
        volume_->dispatch(field, rays.blendRays, jobs.size(), irradiance_.id(), distance_.id(), probeData_.id());
        glEndQuery(GL_TIME_ELAPSED);
    }

    const BlendParams bp = BlendParams::from(field.desc());
    auto run = [&](gl::Program& program, GLuint atlas, int texels) {
        program.use();
        program.set("uTexels", texels);
        program.set("uRays", rays.blendRays);
        program.set("uGamma", bp.irradianceGamma);
        program.set("uIrradianceThreshold", bp.irradianceThreshold);
        program.set("uBrightnessThreshold", bp.brightnessThreshold);
        program.set("uBackfaceScale", kBackfaceDistanceScale);
        glBindImageTexture(0, atlas, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
        GLuint groups = GLuint((texels + 7) / 8);
        glDispatchCompute(groups, groups, GLuint(jobs.size()));
    };
    glBeginQuery(GL_TIME_ELAPSED, blendQuery_.id());
    run(blendIrradiance_, irradiance_.id(), bp.irradianceTexels);
    run(blendDistance_, distance_.id(), bp.distanceTexels);
    glEndQuery(GL_TIME_ELAPSED);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
    glFinish();
    times_.blendGpuMs = gl::timerQueryMs(blendQuery_.id());
    if (shadeHere) times_.shadeGpuMs = gl::timerQueryMs(shadeQuery_.id());
}

void DdgiGpu::border(ProbeField& field, const std::vector<BlendJob>& jobs) {
    if (!jobs.empty()) {
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, jobs_.id());
        border_.use();
        auto run = [&](GLuint atlas, int texels, int isDistance) {
            border_.set("uTexels", texels);
            border_.set("uDistance", isDistance);
            glBindImageTexture(0, atlas, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
            GLuint groups = GLuint((texels + 2 + 7) / 8);
            glDispatchCompute(groups, groups, GLuint(jobs.size()));
        };
        glBeginQuery(GL_TIME_ELAPSED, borderQuery_.id());
        run(irradiance_.id(), field.desc().irradianceTexels, 0);
        run(distance_.id(), field.desc().distanceTexels, 1);
        glEndQuery(GL_TIME_ELAPSED);
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
        glFinish();
        times_.borderGpuMs = gl::timerQueryMs(borderQuery_.id());
    }
    if (volume_) {
        cpuStale_ = true;
        return;
    }
    const auto start = std::chrono::steady_clock::now();
    readBack(field);
    times_.readbackMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
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
