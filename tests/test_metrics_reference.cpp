// Image metrics checked against independent reference code (issue 15): HDR-FLIP against the
// values NVIDIA's FLIP v1.6 gave for the images in ../shared/metrics-reference, and PSNR, SSIM
// and Pearson against scikit-image / SciPy (tests/metrics_vs_skimage.py) on those images and
// on synthetic ones. Each test skips when what it compares against is absent.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <random>
#include <regex>
#include <sstream>

#include "gi/metrics/image_metrics.h"
#include "support/test_support.h"

using namespace voxgi;

namespace {

struct FlipReference {
    std::string test, reference;
    double flip = 0.0;
};

// The README's table rows "| test.exr | reference.exr | mean HDR-FLIP |": the values come from
// NVIDIA's tool, so they are read from where they are published rather than copied here.
std::vector<FlipReference> readFlipTable(const std::string& readme) {
    std::ifstream in(readme);
    std::vector<FlipReference> rows;
    const std::regex row(R"(^\|\s*(\S+\.exr)\s*\|\s*(\S+\.exr)\s*\|\s*([0-9]*\.[0-9]+)\s*\|)");
    std::smatch m;
    for (std::string line; std::getline(in, line);)
        if (std::regex_search(line, m, row)) rows.push_back({m[1], m[2], std::stod(m[3])});
    return rows;
}

void writeFloats(const std::string& path, const std::vector<float>& values) {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(values.data()), std::streamsize(values.size() * sizeof(float)));
}

// What SSIM and Pearson see (docs/reference.md): display values for RGB layers, linear otherwise.
std::vector<float> displayOf(const ImageLayer& layer) {
    if (layer.channels != 3) return layer.data;
    std::vector<float> out(layer.data.size());
    for (std::size_t i = 0; i < out.size(); i += 3) {
        glm::vec3 c = toneMapToSrgb(glm::vec3(layer.data[i], layer.data[i + 1], layer.data[i + 2]), 0.0f);
        for (int k = 0; k < 3; ++k) out[i + std::size_t(k)] = c[k];
    }
    return out;
}

// Deterministic structured HDR content plus noise, non-square so a transposed window would show.
Image synthetic(int w, int h, int channels, unsigned seed, float noise) {
    Image img(w, h);
    ImageLayer& l = img.layer(channels == 3 ? "beauty" : "depth", channels);
    std::mt19937 rng(seed);
    auto uniform01 = [&] { return float(rng() >> 8) / float(1u << 24); };
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < channels; ++c) {
                float base = 0.3f + 0.25f * std::sin(0.4f * float(x) + 1.3f * float(c)) * std::cos(0.3f * float(y));
                if ((x / 6 + y / 5) % 3 == 0) base *= 4.0f;  // blocks brighter than 1 (HDR)
                if (channels == 1) base = 2.0f + 5.0f * base;  // depth-like, offset from 0
                l.data[(std::size_t(y) * std::size_t(w) + std::size_t(x)) * std::size_t(channels) + std::size_t(c)] =
                    base * (1.0f + noise * (uniform01() - 0.5f));
            }
    return img;
}

}  // namespace

TEST(MetricsReference, HdrFlipMatchesNvidiaFlip) {
    const std::string dir = test::sharedDataDir("metrics-reference");
    if (dir.empty()) GTEST_SKIP() << "../shared/metrics-reference not present";
    const std::vector<FlipReference> rows = readFlipTable(dir + "/README.md");
    ASSERT_FALSE(rows.empty()) << "no HDR-FLIP rows in " << dir << "/README.md";
    for (const FlipReference& row : rows) {
        Image test = readExr(dir + "/" + row.test), reference = readExr(dir + "/" + row.reference);
        double flip = computeMetrics(test, reference, "beauty").flip;
        std::printf("HDR-FLIP %s vs %s: voxgi %.6f, NVIDIA FLIP v1.6 %.6f, difference %+.2e\n", row.test.c_str(),
                    row.reference.c_str(), flip, row.flip, flip - row.flip);
        // The README's stated agreement for an implementation of the metric.
        EXPECT_NEAR(flip, row.flip, 1e-3) << row.test;
    }
}

TEST(MetricsReference, PsnrSsimPearsonMatchScikitImage) {
    const std::string python = test::pythonWith("skimage.metrics, scipy.stats");
    if (python.empty()) GTEST_SKIP() << "no python3 with scikit-image and SciPy (Debian python3-skimage)";

    struct Case {
        std::string name;
        Image test, reference;
        std::string layer;
    };
    std::vector<Case> cases;
    const std::string shared = test::sharedDataDir("metrics-reference");
    if (!shared.empty())
        for (const char* name : {"direct", "clpv"})
            cases.push_back({name, readExr(shared + "/" + name + ".exr"), readExr(shared + "/reference.exr"), "beauty"});
    cases.push_back({"synthetic-rgb", synthetic(37, 23, 3, 1, 0.6f), synthetic(37, 23, 3, 2, 0.1f), "beauty"});
    cases.push_back({"synthetic-depth", synthetic(29, 41, 1, 3, 0.4f), synthetic(29, 41, 1, 4, 0.05f), "depth"});

    const std::string dir = test::makeTempDir("skimage");
    std::ofstream list(dir + "/cases.txt");
    std::map<std::string, ImageMetrics> voxgi;
    for (const Case& c : cases) {
        const ImageLayer& t = *c.test.find(c.layer);
        const ImageLayer& r = *c.reference.find(c.layer);
        list << c.name << ' ' << c.reference.width() << ' ' << c.reference.height() << ' ' << r.channels << '\n';
        writeFloats(dir + "/" + c.name + ".test.f32", t.data);
        writeFloats(dir + "/" + c.name + ".ref.f32", r.data);
        writeFloats(dir + "/" + c.name + ".test-display.f32", displayOf(t));
        writeFloats(dir + "/" + c.name + ".ref-display.f32", displayOf(r));
        voxgi[c.name] = computeMetrics(c.test, c.reference, c.layer);
    }
    list.close();

    FILE* pipe = popen(("\"" + python + "\" \"" + test::sourcePath("tests/metrics_vs_skimage.py") + "\" \"" + dir +
                        "\" 2>&1").c_str(),
                       "r");
    ASSERT_NE(pipe, nullptr);
    std::string output;
    char buf[4096];
    for (std::size_t n; (n = fread(buf, 1, sizeof buf, pipe)) > 0;) output.append(buf, n);
    ASSERT_EQ(pclose(pipe), 0) << output;

    std::istringstream lines(output);
    std::string name, metric;
    double value = 0.0;
    int compared = 0;
    while (lines >> name >> metric >> value) {
        ASSERT_TRUE(voxgi.count(name)) << output;
        const ImageMetrics& m = voxgi[name];
        double ours = metric == "psnr" ? m.psnr : metric == "ssim" ? m.ssim : metric == "pearson" ? m.pearson : NAN;
        std::printf("%-16s %-8s voxgi %.8f  skimage/scipy %.8f  difference %+.2e\n", name.c_str(), metric.c_str(),
                    ours, value, ours - value);
        EXPECT_NEAR(ours, value, 1e-4) << name << " " << metric;
        ++compared;
    }
    EXPECT_EQ(compared, 3 * int(cases.size())) << output;
}
