// voxgi reference: the unbiased path-traced image every method is measured against. Writes one
// EXR with the AOV layers (beauty, direct, indirect, albedo, normal, depth).
#include <algorithm>
#include <cmath>
#include <chrono>
#include <cstdio>

#include "gi/pathtrace/path_tracer.h"
#include "scenes/errors.h"
#include "scenes/image.h"
#include "tools/commands.h"
#include "tools/display_args.h"
#include "tools/scene_arg.h"

namespace voxgi::cli {

namespace {

const char* kUsage =
    "voxgi reference SCENE (--spp N | --time SECONDS) -o OUT.exr [--max-bounces B] [--seed S] [--unidirectional]\n"
    "       [--no-caustics] [--width W --height H] [--png OUT.png] [--exposure auto|STOPS] [--tonemap filmic|reinhard] [--set section.key=value]...\n"
    "  --max-bounces: scattering events per path (1 = direct light only; default unlimited, Russian roulette)\n"
    "  --unidirectional: camera paths only, without connections to light subpaths from point and spot\n"
    "  lights (the same image in expectation, noisier; docs/reference.md)\n"
    "  --no-caustics: leave out caustics, light that reaches a diffuse surface by a specular reflection or a\n"
    "  refraction (what methods that trace only the camera's reflections aim at; not the physical image,\n"
    "  docs/reference.md)" VOXGI_DISPLAY_USAGE;

using Clock = std::chrono::steady_clock;

void printProgress(double fraction, double elapsed, int spp) {
    const int width = 30;
    int filled = int(std::clamp(fraction, 0.0, 1.0) * width);
    double eta = fraction > 0.0 ? elapsed * (1.0 - fraction) / fraction : 0.0;
    std::fprintf(stderr, "\r[%.*s%*s] %5.1f%%  %d spp  %.1f s, ETA %.1f s ", filled,
                 "##############################", width - filled, "", 100.0 * fraction, spp, elapsed, eta);
    std::fflush(stderr);
}

int runReference(const std::vector<std::string>& argv) {
    Args args(argv, {"--spp", "--time", "-o", "--max-bounces", "--seed", "--width", "--height", "--png", "--exposure", "--tonemap", "--set"},
              {"--quiet", "--unidirectional", "--no-caustics"}, {"--set"});
    args.requirePositional(1, kUsage);
    if (args.has("--spp") == args.has("--time")) throw InputError("give exactly one of --spp N or --time SECONDS");
    auto out = args.value("-o");
    if (!out) throw InputError("-o OUT.exr is required; usage: " + usageLine(kUsage));
    requireOutputs(args, {"-o", "--png"});
    const int spp = args.integer("--spp", 0, 1, 1 << 24);
    const double seconds = args.number("--time", 0.0, 1e-3, 1e7);
    const DisplayArgs display = displayArguments(args);
    PathTracerOptions options;
    options.maxBounces = args.integer("--max-bounces", 0, 0, 1 << 20);
    options.seed = std::uint64_t(args.number("--seed", 0.0, 0.0, 9007199254740992.0));
    options.lightPaths = !args.flag("--unidirectional");
    options.caustics = !args.flag("--no-caustics");

    Scene scene = loadSceneArgument(args.positional()[0]);
    applySceneOverrides(args, scene);
    const bool quiet = args.flag("--quiet");

    auto start = Clock::now();
    PathTracer tracer(scene, options);
    double setup = std::chrono::duration<double>(Clock::now() - start).count();
    auto renderStart = Clock::now();
    auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - renderStart).count(); };
    // One sample per pixel per pass keeps the progress bar and --time responsive; a pass over a
    // tiny image is cheap, so passes grow until each takes about 0.1 s.
    int pass = 1;
    while (true) {
        int done = tracer.samplesPerPixel();
        if (spp > 0 && done >= spp) break;
        if (spp == 0 && done > 0 && elapsed() >= seconds) break;
        int n = spp > 0 ? std::min(pass, spp - done) : pass;
        auto passStart = Clock::now();
        tracer.render(n);
        double passTime = std::chrono::duration<double>(Clock::now() - passStart).count();
        if (passTime < 0.05 && pass < 1024) pass *= 2;
        if (spp == 0 && elapsed() + passTime * (double(pass) / double(n)) > seconds && pass > 1) pass = 1;
        if (!quiet) {
            double fraction = spp > 0 ? double(tracer.samplesPerPixel()) / spp : std::min(elapsed() / seconds, 1.0);
            printProgress(fraction, elapsed(), tracer.samplesPerPixel());
        }
    }
    double renderTime = elapsed();
    if (!quiet) std::fprintf(stderr, "\n");

    Image image = tracer.image();
    // Samples that came out NaN or infinite are dropped; more than one in a thousand is no
    // longer a rare accident but a scene whose values overflow float, and the image would be
    // biased (or black): refuse it.
    const double samples = double(tracer.width()) * double(tracer.height()) * double(tracer.samplesPerPixel());
    if (double(tracer.droppedSamples()) > 1e-3 * samples)
        throw InputError(args.positional()[0] + ": " + std::to_string(tracer.droppedSamples()) + " of " +
                         std::to_string((long long)samples) +
                         " samples were NaN or infinite (values overflow float: lights or emission too bright?)");
    // Samples are finite, but their mean in float can still overflow: refuse the image rather
    // than write infinities.
    for (const char* layer : {"beauty", "direct", "indirect"}) {
        const std::vector<float>& data = image.layer(layer).data;
        const auto bad = std::count_if(data.begin(), data.end(), [](float v) { return !std::isfinite(v); });
        if (bad > 0)
            throw InputError(args.positional()[0] + ": " + std::to_string(bad) + " values of the " + layer +
                             " layer overflow float: lights or emission too bright");
    }
    image.display = resolveDisplay(display, image);
    writeExr(*out, image);
    if (auto png = args.value("--png"))
        writePng(*png, image, "beauty", image.display.exposureStops, image.display.toneCurve);
    double raysPerSecond = renderTime > 0.0 ? double(tracer.raysTraced()) / renderTime : 0.0;
    std::printf("path traced %s: %dx%d, %d spp, max bounces %s, seed %llu%s\n", args.positional()[0].c_str(),
                tracer.width(), tracer.height(), tracer.samplesPerPixel(),
                options.maxBounces > 0 ? std::to_string(options.maxBounces).c_str() : "unlimited",
                static_cast<unsigned long long>(options.seed), options.caustics ? "" : ", no caustics");
    std::printf("time %.2f s (+ %.2f s BVH build), %llu rays, %.2f M rays/s, dropped NaN/Inf samples: %llu\n",
                renderTime, setup, static_cast<unsigned long long>(tracer.raysTraced()), raysPerSecond * 1e-6,
                static_cast<unsigned long long>(tracer.droppedSamples()));
    std::printf("wrote %s%s\n", out->c_str(), args.has("--png") ? (" and " + *args.value("--png")).c_str() : "");
    return kOk;
}

}  // namespace

VOXGI_REGISTER_COMMAND("reference", kUsage, runReference);

}  // namespace voxgi::cli
