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
    "  --aov: the layer to compare (default beauty); --diff: HDR-FLIP error map (colour layers)\n"
    "  or |difference| scaled to its maximum (1-channel layers); --regions: the layer's mean in each\n"
    "  of the scene's regions, test against reference (the reference must be voxgi reference's)";

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

int runCompare(const std::vector<std::string>& argv) {
    Args args(argv, {"--aov", "--diff", "--json", "--regions"}, {});
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
        std::printf("  region            pixels    test mean (rgb)            reference mean (rgb)       test/ref\n");
        for (const RegionMean& r : regions)
            std::printf("  %-16s %7zu    %8.4g %8.4g %8.4g   %8.4g %8.4g %8.4g   %.3f\n", r.name.c_str(), r.pixels,
                        r.test.x, r.test.y, r.test.z, r.reference.x, r.reference.y, r.reference.z, r.ratio);
    }
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
                                {"ratio", std::isfinite(r.ratio) ? nlohmann::ordered_json(r.ratio) : nlohmann::ordered_json()}});
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
