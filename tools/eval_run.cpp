#include "tools/eval_run.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <string_view>

#include <nlohmann/json.hpp>

#include "gi/pathtrace/path_tracer.h"
#include "gl/timers.h"
#include "render/frame/frame_renderer.h"
#include "scenes/atomic_file.h"
#include "scenes/errors.h"

namespace voxgi::cli {

namespace {
using Clock = std::chrono::steady_clock;

double median(std::vector<double> v) { return gl::summarize(std::move(v)).median; }

std::vector<double> tailFrom(const std::vector<double>& v, std::size_t from) {
    return from < v.size() ? std::vector<double>(v.begin() + std::ptrdiff_t(from), v.end()) : std::vector<double>{};
}

// Everything the picture depends on, so a changed scene or camera never reuses a stale file.
std::string sceneKey(const Scene& scene) {
    std::ostringstream s;
    s.precision(9);
    const Camera& c = scene.camera;
    s << c.eye.x << c.eye.y << c.eye.z << c.target.x << c.target.y << c.target.z << c.fovYDegrees << c.width << 'x'
      << c.height << '|';
    for (const Light& l : scene.lights)
        s << int(l.type) << l.position.x << l.position.y << l.position.z << l.emission.x << l.emission.y << l.emission.z
          << l.direction.x << l.direction.y << l.direction.z << l.angularDiameterDegrees << '|';
    for (const Material& m : scene.materials)
        s << m.albedo.x << m.albedo.y << m.albedo.z << m.emission.x << m.roughness << m.metallic << m.specular << '|';
    for (const Mesh& m : scene.meshes) {
        s << m.positions.size() << ':' << m.indices.size();
        for (const glm::vec3& p : m.positions) s << p.x << p.y << p.z;
    }
    s << scene.sky.enabled << scene.sky.radiance.x;
    if (scene.sky.tabulated())
        s << int(scene.sky.type) << scene.sky.width << 'x' << scene.sky.height << ':'
          << std::hash<std::string_view>{}(std::string_view(reinterpret_cast<const char*>(scene.sky.table.data()),
                                                             scene.sky.table.size() * sizeof(glm::vec3)));
    s << "|pt" << kPathTracerRevision;
    std::ostringstream hex;
    hex << std::hex << std::hash<std::string>{}(s.str());
    return hex.str();
}
}  // namespace

struct MethodSession::Impl {
    Scene scene;  // the renderer reads it every frame: the camera moves here
    FrameRenderer renderer;
    RenderSettings settings;

    static FrameOptions options(const RenderSettings& settings) {
        FrameOptions o;
        o.width = settings.width;
        o.height = settings.height;
        // Timed frames do all their work, as lpv.reuse=false makes the LPV's: a still camera would
        // keep the sun's maps and time a frame no moving camera gets.
        o.keepSunMaps = false;
        return o;
    }
    Impl(const Scene& s, const std::string& method, const RenderSettings& rs)
        : scene(s), renderer(scene, options(rs), method), settings(rs) {}
};

namespace {
Scene withSettings(const Scene& base, const Preset& preset, const SettingList& extra) {
    Scene scene = base;
    for (const auto& [k, v] : preset.settings) scene.gi.set(k, v);
    for (const auto& [k, v] : extra) scene.gi.set(k, v);
    return scene;
}
}  // namespace

MethodSession::MethodSession(const Scene& scene, const std::string& method, const Preset& preset,
                             const RenderSettings& settings, const SettingList& extra)
    : impl_(std::make_unique<Impl>(withSettings(scene, preset, extra), method, settings)) {
    if (GiTechnique* technique = impl_->renderer.technique()) technique->trackConvergence();
}

MethodSession::~MethodSession() = default;

MethodRun MethodSession::render(const Camera& camera) {
    const RenderSettings& settings = impl_->settings;
    FrameRenderer& renderer = impl_->renderer;
    impl_->scene.camera = camera;
    renderer.resetAccumulation();
    MethodRun run;
    const int warmup = std::min(settings.warmup, settings.frames - 1);
    run.timedFrames = settings.frames - warmup;
    GiTechnique* technique = renderer.technique();
    run.temporal = technique && technique->lightStateChange().has_value();
    // Warm-up: a fixed number of frames, or for a temporal technique until its light settles.
    auto settled = [&] {
        if (!run.temporal) return run.warmupFrames >= warmup;
        const double change = *technique->lightStateChange();
        run.converged = change >= 0.0 && change < settings.convergeBelow;
        return run.warmupFrames >= warmup && (run.converged || run.warmupFrames >= settings.maxWarmup);
    };
    while (!settled()) {
        auto start = Clock::now();
        renderer.renderFrame();
        run.convergeMs += std::chrono::duration<double, std::milli>(Clock::now() - start).count();
        ++run.warmupFrames;
    }
    std::map<std::string, std::size_t> gpuStart, cpuStart;
    for (const auto& [stage, s] : renderer.timers().samples()) {
        gpuStart[stage] = s.gpuMs.size();
        cpuStart[stage] = s.cpuMs.size();
    }
    // The timed frames start the frame sequence again (camera jitter, the sun's PCSS rotation,
    // area-light points): every method's image then averages the same frames, so their direct
    // light differs only by what the method adds. After different warm-ups (4 frames, or DDGI's
    // until its field settles) direct light alone moved the full-image RMSE on Sponza at noon
    // from 0.00706 to 0.00663 (frames 4-11 against 100-107).
    renderer.resetAccumulation();
    std::vector<double> frameMs;
    std::map<std::string, std::vector<double>> stats;
    for (int f = 0; f < run.timedFrames; ++f) {
        auto start = Clock::now();
        renderer.renderFrame();
        double ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
        frameMs.push_back(ms);
        if (const GiTechnique* t = renderer.technique())
            for (const TechniqueStat& st : t->stats()) stats[st.unit == "ms" ? st.name + "_ms" : st.name].push_back(st.value);
    }
    run.frameMs = median(frameMs);
    for (const auto& [name, values] : stats) run.stats.emplace_back(name, median(values));
    const auto& samples = renderer.timers().samples();
    for (const std::string& stage : renderer.timers().stageOrder()) {
        auto it = samples.find(stage);
        if (it == samples.end()) continue;
        StageTiming t;
        t.gpuMs = median(tailFrom(it->second.gpuMs, gpuStart.count(stage) ? gpuStart[stage] : 0));
        const std::vector<double> cpu = tailFrom(it->second.cpuMs, cpuStart.count(stage) ? cpuStart[stage] : 0);
        t.cpuMs = median(cpu);
        t.samples = cpu.size();
        run.stages.emplace_back(stage, t);
    }
    run.image = renderer.resolve();
    return run;
}

MethodRun renderMethod(const Scene& base, const std::string& method, const Preset& preset,
                       const RenderSettings& settings, const SettingList& extra) {
    return MethodSession(base, method, preset, settings, extra).render(base.camera);
}

Reference loadOrRenderReference(const Scene& scene, const std::string& name, int spp, const std::string& cacheDir,
                                bool caustics) {
    namespace fs = std::filesystem;
    std::error_code ec;
    fs::create_directories(cacheDir, ec);
    if (ec) throw InputError(cacheDir + ": cannot create the reference cache (" + ec.message() + ")");
    const std::string stem = cacheDir + "/" + name + "-" + std::to_string(scene.camera.width) + "x" +
                             std::to_string(scene.camera.height) + "-" + std::to_string(spp) + "spp-" + (caustics ? "" : "nocaustics-") +
                             sceneKey(scene);
    Reference ref;
    ref.path = stem + ".exr";
    ref.spp = spp;
    if (fs::exists(ref.path) && fs::exists(stem + ".json")) {
        ref.image = readExr(ref.path);
        std::ifstream in(stem + ".json");
        nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
        ref.seconds = j.is_object() ? j.value("seconds", 0.0) : 0.0;
        ref.fromCache = true;
        return ref;
    }
    auto start = Clock::now();
    PathTracerOptions options;
    options.caustics = caustics;
    PathTracer tracer(scene, options);
    // Passes of a few samples keep memory flat and let a slow scene print progress.
    while (tracer.samplesPerPixel() < spp) {
        tracer.render(std::min(8, spp - tracer.samplesPerPixel()));
        std::fprintf(stderr, "\r  reference %s: %d/%d spp", name.c_str(), tracer.samplesPerPixel(), spp);
    }
    std::fprintf(stderr, "\n");
    ref.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    ref.image = tracer.image();
    // The cache is not the command's output: it stays even if the command fails later.
    OutputBatch::Immediate cache;
    writeExr(ref.path, ref.image);
    writeTextAtomically(stem + ".json",
                        nlohmann::json{{"spp", spp}, {"seconds", ref.seconds}, {"rays", tracer.raysTraced()}}.dump(2) + "\n");
    return ref;
}

Reference readReference(const std::string& path, const Scene& scene) {
    Reference ref;
    ref.path = path;
    ref.image = readExr(path);
    ref.fromCache = true;
    if (ref.image.width() != scene.camera.width || ref.image.height() != scene.camera.height)
        throw InputError("--reference " + path + ": " + std::to_string(ref.image.width()) + "x" +
                         std::to_string(ref.image.height()) + " does not match the render size " +
                         std::to_string(scene.camera.width) + "x" + std::to_string(scene.camera.height));
    if (!ref.image.find("indirect"))
        throw InputError("--reference " + path + ": no indirect layer (write it with voxgi reference)");
    return ref;
}

}  // namespace voxgi::cli
