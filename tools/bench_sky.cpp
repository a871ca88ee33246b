// voxgi bench sky: what the sky-lighting volume costs the CPU when the sky is built and when it
// changes (the sky issue's speed goals: a whole build within 1 s on 2 cores, then at most
// sky.update_ms a frame). Per scene with an atmosphere: the first frame's whole build, then the
// sun turned about the vertical (followSun remakes the table) and the frames until the volume
// traced again under the new sky replaces the old one, with the CPU time of each.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>

#include "gl/context.h"
#include "gi/sky/sky_volume.h"
#include "gl/timers.h"
#include "render/frame/frame_renderer.h"
#include "scenes/errors.h"
#include "scenes/sky_model.h"
#include "tools/args.h"
#include "tools/bench_registry.h"
#include "tools/scene_arg.h"

namespace voxgi::cli {

namespace {

const char* kUsage =
    "voxgi bench sky [SCENE...] [--size 512] [--turn 15] [--method direct] [--set k=v]...\n"
    "  SCENE: default outdoor and, when ../shared/scenes is there, sponza-noon and sibenik-noon (a\n"
    "  scene needs an atmosphere and its sun). The CPU ms of the sky-lighting volume's whole build,\n"
    "  of the sky's table when the sun turns by --turn degrees about the vertical, and of each frame\n"
    "  that traces the volume again (sky.update_ms a frame)";

// The CPU samples of the frame's `sky_volume` stage so far.
std::size_t skySamples(FrameRenderer& r) {
    const auto& samples = r.timers().samples();
    const auto it = samples.find("sky_volume");
    return it == samples.end() ? 0 : it->second.cpuMs.size();
}

int benchSky(const std::vector<std::string>& argv) {
    Args args(argv, {"--size", "--turn", "--method", "--set"}, {}, {"--set"});
    const int size = args.integer("--size", 512, 8, 8192);
    const float turn = float(args.number("--turn", 15.0, -360.0, 360.0));
    const std::string method = args.value("--method", "direct");
    const bool given = !args.positional().empty();
    const std::vector<std::string> names =
        given ? args.positional() : std::vector<std::string>{"outdoor", "sponza-noon", "sibenik-noon"};
    std::vector<std::pair<std::string, Scene>> scenes;
    for (const std::string& name : names) {
        std::optional<Scene> scene = loadBenchScene(name);
        if (!scene) continue;
        applySceneOverrides(args, *scene);
        if (!atmosphereSun(*scene)) {
            if (given) throw InputError(name + ": the sky benchmark needs an atmosphere sky with its sun");
            std::printf("%s: skipped (no atmosphere with a sun)\n", name.c_str());
            continue;
        }
        scene->camera.width = scene->camera.height = size;
        scenes.emplace_back(name, std::move(*scene));
    }
    const std::unique_ptr<gl::Context> context = gl::Context::createHeadless();
    std::printf("sky-lighting volume, %s at %d^2, sun turned %g degrees (%s; CPU ms)\n", method.c_str(), size, double(turn),
                context->description().c_str());
    for (auto& [name, scene] : scenes) {
        FrameOptions options;
        options.jitter = false;
        FrameRenderer r(scene, options, method);
        r.renderFrame();
        const double whole = skySamples(r) > 0 ? r.timers().samples().at("sky_volume").cpuMs.back() : 0.0;
        Light& sun = *atmosphereSun(scene);
        sun.direction = glm::vec3(glm::rotate(glm::mat4(1.0f), glm::radians(turn), glm::vec3(0, 1, 0)) * glm::vec4(sun.direction, 0.0f));
        const auto t0 = std::chrono::steady_clock::now();
        const bool moved = followSun(scene);
        const double table = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        if (!moved) {
            std::printf("%-28s whole build %8.1f; the turned sun is not above the horizon\n", name.c_str(), whole);
            continue;
        }
        // Frames until one adds no sample: the volume was whole the frame before.
        std::vector<double> perFrame;
        for (int frame = 0; frame < 100000; ++frame) {
            const std::size_t before = skySamples(r);
            r.renderFrame();
            if (skySamples(r) == before) break;
            perFrame.push_back(r.timers().samples().at("sky_volume").cpuMs.back());
        }
        double sum = 0.0;
        for (double ms : perFrame) sum += ms;
        std::vector<double> sorted = perFrame;
        std::sort(sorted.begin(), sorted.end());
        const double median = sorted.empty() ? 0.0 : sorted[sorted.size() / 2];
        const double worst = sorted.empty() ? 0.0 : sorted.back();
        const double budget = readSkyVolumeDesc(scene.gi).updateMs;
        const auto over = std::count_if(sorted.begin(), sorted.end(), [&](double ms) { return ms > budget; });
        std::printf("%-28s whole build %8.1f, table %6.1f; traced again over %zu frames: %.2f median, %.2f max, %.1f in all, "
                    "%d over the %.3g ms budget\n",
                    name.c_str(), whole, table, perFrame.size(), median, worst, sum, int(over), budget);
        std::fflush(stdout);
    }
    return kOk;
}

}  // namespace

VOXGI_REGISTER_BENCHMARK("sky", kUsage, benchSky);

}  // namespace voxgi::cli
