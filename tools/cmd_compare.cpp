// voxgi compare: error metrics of a test image against a reference (gi/metrics), printed,
// optionally as JSON, with an optional error-map PNG (HDR-FLIP for colour layers).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>

#include <nlohmann/json.hpp>

#include "gi/metrics/flip.h"
#include "gi/metrics/image_metrics.h"
#include "gi/metrics/regions.h"
#include "scenes/atomic_file.h"
#include "scenes/errors.h"
#include "scenes/image.h"
#include "tools/commands.h"
#include "tools/scene_arg.h"

namespace voxgi::cli {

namespace {

const char* kUsage =
    "voxgi compare TEST.exr REFERENCE.exr [--aov NAME] [--diff DIFF.png] [--json OUT.json] [--regions SCENE]\n"
    "       [--worst N]\n"
    "  --aov: the layer to compare (default beauty); --diff: HDR-FLIP error map (colour layers)\n"
    "  or |difference| scaled to its maximum (1-channel layers); --regions: the layer's mean in each\n"
    "  of the scene's regions, test against reference (the reference must be voxgi reference's);\n"
    "  --worst: the N pixels with the largest share of relMSE, with both values";

// Black -> red -> yellow -> white: error 0 stays black, 1 is white.
glm::vec3 heat(float e) {
    e = std::clamp(e, 0.0f, 1.0f);
    return glm::clamp(glm::vec3(3.0f * e, 3.0f * e - 1.0f, 3.0f * e - 2.0f), 0.0f, 1.0f);
}

void writeDiff(const std::string& path, const Image& test, const Image& reference, const std::string& layer) {
    const ImageLayer& t = *test.find(layer);
    const ImageLayer& r = *reference.find(layer);
    std::vector<float> error;
    if (r.channels == 3) {
        error = flip::hdrFlip(t.data, r.data, reference.width(), reference.height()).error;
    } else {
        error.resize(reference.pixelCount());
        float largest = 0.0f;
        for (std::size_t i = 0; i < error.size(); ++i) largest = std::max(largest, error[i] = std::abs(t.data[i] - r.data[i]));
        if (largest > 0.0f)
            for (float& e : error) e /= largest;
    }
    std::vector<std::uint8_t> rgb(3 * error.size());
    for (std::size_t i = 0; i < error.size(); ++i) {
        glm::vec3 c = heat(error[i]);
        for (int k = 0; k < 3; ++k) rgb[3 * i + std::size_t(k)] = std::uint8_t(std::lround(255.0f * c[k]));
    }
    writePngRgb8(path, reference.width(), reference.height(), rgb);
}

// The pixels holding most of relMSE: a handful of them can outweigh a whole image.
void printWorstPixels(const Image& test, const Image& reference, const std::string& layer, int count) {
    const ImageLayer& t = *test.find(layer);
    const ImageLayer& r = *reference.find(layer);
    const std::vector<double> terms = relativeSquaredErrorPerPixel(t.data, r.data, r.channels);
    double total = 0.0;
    for (double e : terms) total += e;
    std::vector<std::size_t> order(terms.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    const std::size_t n = std::min(order.size(), std::size_t(count));
    std::partial_sort(order.begin(), order.begin() + std::ptrdiff_t(n), order.end(),
                      [&](std::size_t a, std::size_t b) { return terms[a] > terms[b]; });
    std::printf("  worst pixels by relMSE share (x y: test | reference, share):\n");
    double shown = 0.0;
    for (std::size_t k = 0; k < n; ++k) {
        const std::size_t i = order[k];
        std::printf("  %4zu %4zu:", i % std::size_t(reference.width()), i / std::size_t(reference.width()));
        for (int c = 0; c < r.channels; ++c) std::printf(" %9.4g", t.data[i * std::size_t(r.channels) + std::size_t(c)]);
        std::printf(" |");
        for (int c = 0; c < r.channels; ++c) std::printf(" %9.4g", r.data[i * std::size_t(r.channels) + std::size_t(c)]);
        std::printf("   %5.1f %%\n", total > 0.0 ? 100.0 * terms[i] / total : 0.0);
        shown += terms[i];
    }
    std::printf("  these %zu of %zu pixels: %.1f %% of relMSE\n", n, terms.size(), total > 0.0 ? 100.0 * shown / total : 0.0);
}

int runCompare(const std::vector<std::string>& argv) {
    Args args(argv, {"--aov", "--diff", "--json", "--regions", "--worst"}, {});
    const int worst = args.integer("--worst", 0, 0, 1 << 20);
    args.requirePositional(2, kUsage);
    const std::string layer = args.value("--aov", "beauty");
    requireOutputs(args, {"--diff", "--json"}, {"--regions"});
    Image test = readExr(args.positional()[0]);
    Image reference = readExr(args.positional()[1]);
    // Metrics of an image holding NaN or infinity are NaN: refuse instead of printing them.
    for (std::size_t i = 0; i < 2; ++i) {
        const Image& image = i == 0 ? test : reference;
        const ImageLayer* l = image.find(layer);
        if (!l) continue;  // computeMetrics names the missing layer
        const auto bad = std::count_if(l->data.begin(), l->data.end(), [](float v) { return !std::isfinite(v); });
        if (bad > 0)
            throw InputError(args.positional()[i] + ": layer " + layer + " holds " + std::to_string(bad) +
                             " NaN or infinite values");
    }
    ImageMetrics m = computeMetrics(test, reference, layer);
    std::vector<RegionMean> regions;
    if (auto sceneArg = args.value("--regions")) {
        const Scene scene = loadSceneArgument(*sceneArg);
        if (scene.regions.empty()) throw InputError(*sceneArg + ": regions: the scene declares none");
        regions = regionMeans(test, reference, scene, layer);
    }

    std::printf("%s against %s, layer %s (%dx%d, %d channel%s)\n", args.positional()[0].c_str(),
                args.positional()[1].c_str(), layer.c_str(), reference.width(), reference.height(), m.channels,
                m.channels == 1 ? "" : "s");
    std::printf("  MSE        %.6g\n  RMSE       %.6g\n  relMSE     %.6g   (eps %.0e)\n  MAE        %.6g\n",
                m.mse, m.rmse, m.relMse, kRelMseEpsilon, m.mae);
    std::printf("  PSNR       %.3f dB\n  SSIM       %.5f\n  mean error %.4f   (seed 003 Eq. 19)\n", m.psnr, m.ssim,
                m.meanError);
    std::printf("  Pearson    %.5f   (seed 003 Eq. 20)\n  HDR-FLIP   %.5f\n", m.pearson, m.flip);
    if (!regions.empty()) {
        std::printf("  region            pixels    test mean (rgb)            reference mean (rgb)       test/ref   relMSE      HDR-FLIP\n");
        for (const RegionMean& r : regions)
            std::printf("  %-16s %7zu    %8.4g %8.4g %8.4g   %8.4g %8.4g %8.4g   %-8.3f   %-9.4g   %.4f\n", r.name.c_str(),
                        r.pixels, r.test.x, r.test.y, r.test.z, r.reference.x, r.reference.y, r.reference.z, r.ratio,
                        r.relMse, r.flip);
    }
    if (worst > 0) printWorstPixels(test, reference, layer, worst);
    if (auto d = args.value("--diff")) {
        writeDiff(*d, test, reference, layer);
        std::printf("wrote %s\n", d->c_str());
    }
    if (auto j = args.value("--json")) {
        nlohmann::ordered_json json = nlohmann::ordered_json::parse(toJson(m));
        if (!regions.empty()) {
            nlohmann::ordered_json list = nlohmann::ordered_json::array();
            for (const RegionMean& r : regions)
                list.push_back({{"name", r.name},
                                {"pixels", r.pixels},
                                {"test", {r.test.x, r.test.y, r.test.z}},
                                {"reference", {r.reference.x, r.reference.y, r.reference.z}},
                                {"ratio", std::isfinite(r.ratio) ? nlohmann::ordered_json(r.ratio) : nlohmann::ordered_json()},
                                {"relmse", r.pixels ? nlohmann::ordered_json(r.relMse) : nlohmann::ordered_json()},
                                {"flip", r.pixels ? nlohmann::ordered_json(r.flip) : nlohmann::ordered_json()}});
            json["regions"] = list;
        }
        writeTextAtomically(*j, json.dump(2) + "\n");
        std::printf("wrote %s\n", j->c_str());
    }
    return kOk;
}

}  // namespace

VOXGI_REGISTER_COMMAND("compare", kUsage, runCompare);

}  // namespace voxgi::cli
