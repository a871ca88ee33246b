#include "gi/metrics/image_metrics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "gi/metrics/flip.h"
#include "scenes/errors.h"

namespace voxgi {

namespace {

void requireSameSize(const std::vector<float>& a, const std::vector<float>& b) {
    if (a.size() != b.size() || a.empty()) throw InputError("images to compare differ in size or are empty");
}

// 8-bit display values the way the previews show them, used by the metrics that model a viewer.
std::vector<float> displayValues(const ImageLayer& layer, float scale) {
    std::vector<float> out(layer.data.size());
    for (std::size_t i = 0; i + 2 < layer.data.size(); i += 3) {
        glm::vec3 c = toneMapToSrgb(glm::vec3(layer.data[i], layer.data[i + 1], layer.data[i + 2]), 0.0f);
        for (int k = 0; k < 3; ++k) out[i + std::size_t(k)] = scale * c[k];
    }
    return out;
}

std::vector<double> gaussianWindow() {
    std::vector<double> w(11);
    double sum = 0.0;
    for (int i = -5; i <= 5; ++i) sum += (w[std::size_t(i + 5)] = std::exp(-double(i * i) / (2.0 * 1.5 * 1.5)));
    for (double& v : w) v /= sum;
    return w;
}

std::string number(double v) {
    if (!std::isfinite(v)) return "null";
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.9g", v);
    return buf;
}

}  // namespace

double meanSquaredError(const std::vector<float>& a, const std::vector<float>& b) {
    requireSameSize(a, b);
    double s = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) s += double(a[i] - b[i]) * double(a[i] - b[i]);
    return s / double(a.size());
}

namespace {
double relativeSquaredError(float a, float ref, double epsilon) {
    const double d = double(a) - double(ref);
    return d * d / (double(ref) * double(ref) + epsilon);
}
}  // namespace

double relativeMse(const std::vector<float>& a, const std::vector<float>& ref, double epsilon) {
    requireSameSize(a, ref);
    double s = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) s += relativeSquaredError(a[i], ref[i], epsilon);
    return s / double(a.size());
}

std::vector<double> relativeSquaredErrorPerPixel(const std::vector<float>& a, const std::vector<float>& ref, int channels,
                                                 double epsilon) {
    requireSameSize(a, ref);
    std::vector<double> out(a.size() / std::size_t(std::max(channels, 1)), 0.0);
    for (std::size_t i = 0; i < out.size() * std::size_t(channels); ++i)
        out[i / std::size_t(channels)] += relativeSquaredError(a[i], ref[i], epsilon);
    return out;
}

double meanAbsoluteError(const std::vector<float>& a, const std::vector<float>& b) {
    requireSameSize(a, b);
    double s = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) s += std::abs(double(a[i]) - double(b[i]));
    return s / double(a.size());
}

double peakSignalToNoise(double mse, double peak) {
    if (mse <= 0.0) return std::numeric_limits<double>::infinity();
    return 10.0 * std::log10(peak * peak / mse);
}

double pearsonCorrelation(const std::vector<float>& x, const std::vector<float>& y) {
    requireSameSize(x, y);
    double n = double(x.size()), mx = 0.0, my = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) {
        mx += x[i];
        my += y[i];
    }
    mx /= n;
    my /= n;
    double sxx = 0.0, syy = 0.0, sxy = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) {
        double dx = x[i] - mx, dy = y[i] - my;
        sxx += dx * dx;
        syy += dy * dy;
        sxy += dx * dy;
    }
    // (1/n) sum of standardised products with population deviations (Eq. 20).
    if (sxx <= 0.0 || syy <= 0.0) return std::numeric_limits<double>::quiet_NaN();
    return (sxy / n) / (std::sqrt(sxx / n) * std::sqrt(syy / n));
}

double structuralSimilarity(const std::vector<float>& a, const std::vector<float>& b, int w, int h, int channels,
                            double dynamicRange) {
    requireSameSize(a, b);
    const std::vector<double> window = gaussianWindow();
    const double c1 = (0.01 * dynamicRange) * (0.01 * dynamicRange), c2 = (0.03 * dynamicRange) * (0.03 * dynamicRange);
    auto at = [&](const std::vector<float>& v, int x, int y, int c) {
        return double(v[(std::size_t(std::clamp(y, 0, h - 1)) * std::size_t(w) + std::size_t(std::clamp(x, 0, w - 1))) *
                            std::size_t(channels) + std::size_t(c)]);
    };
    double total = 0.0;
    for (int c = 0; c < channels; ++c)
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                // Two passes (means, then centred moments) so flat windows give exactly zero variance.
                double ma = 0, mb = 0;
                for (int j = -5; j <= 5; ++j)
                    for (int i = -5; i <= 5; ++i) {
                        double wt = window[std::size_t(i + 5)] * window[std::size_t(j + 5)];
                        ma += wt * at(a, x + i, y + j, c);
                        mb += wt * at(b, x + i, y + j, c);
                    }
                double sa = 0, sb = 0, sab = 0;
                for (int j = -5; j <= 5; ++j)
                    for (int i = -5; i <= 5; ++i) {
                        double wt = window[std::size_t(i + 5)] * window[std::size_t(j + 5)];
                        double da = at(a, x + i, y + j, c) - ma, db = at(b, x + i, y + j, c) - mb;
                        sa += wt * da * da;
                        sb += wt * db * db;
                        sab += wt * da * db;
                    }
                total += ((2 * ma * mb + c1) * (2 * sab + c2)) / ((ma * ma + mb * mb + c1) * (sa + sb + c2));
            }
    return total / (double(w) * double(h) * double(channels));
}

ImageMetrics computeMetrics(const Image& test, const Image& reference, const std::string& layerName) {
    const ImageLayer* t = test.find(layerName);
    const ImageLayer* r = reference.find(layerName);
    if (!t) throw InputError("test image has no layer '" + layerName + "'");
    if (!r) throw InputError("reference image has no layer '" + layerName + "'");
    if (test.width() != reference.width() || test.height() != reference.height())
        throw InputError("image sizes differ: " + std::to_string(test.width()) + "x" + std::to_string(test.height()) +
                         " against " + std::to_string(reference.width()) + "x" + std::to_string(reference.height()));
    if (t->channels != r->channels) throw InputError("layer '" + layerName + "' has different channel counts");

    ImageMetrics m;
    m.layer = layerName;
    m.channels = r->channels;
    m.pixels = reference.pixelCount();
    m.mse = meanSquaredError(t->data, r->data);
    m.rmse = std::sqrt(m.mse);
    m.relMse = relativeMse(t->data, r->data);
    m.mae = meanAbsoluteError(t->data, r->data);
    float peak = 0.0f;
    for (float v : r->data) peak = std::max(peak, v);
    m.psnr = peakSignalToNoise(m.mse, peak > 0.0f ? peak : 1.0);
    if (r->channels == 3) {
        std::vector<float> td = displayValues(*t, 1.0f), rd = displayValues(*r, 1.0f);
        m.ssim = structuralSimilarity(td, rd, reference.width(), reference.height(), 3, 1.0);
        for (float& v : td) v *= 255.0f;
        for (float& v : rd) v *= 255.0f;
        m.meanError = meanAbsoluteError(td, rd);  // Eq. 19: (1/3wh) sum |D_r| + |D_g| + |D_b|
        m.pearson = pearsonCorrelation(td, rd);
        m.flip = flip::hdrFlip(t->data, r->data, reference.width(), reference.height()).mean;
    } else {
        // L is the reference's own range (max - min), not max - min(0, min): depth does not start at 0.
        auto [low, high] = std::minmax_element(r->data.begin(), r->data.end());
        double range = double(*high) - double(*low);
        m.ssim = structuralSimilarity(t->data, r->data, reference.width(), reference.height(), r->channels,
                                      range > 0.0 ? range : 1.0);
        m.meanError = m.mae;
        m.pearson = pearsonCorrelation(t->data, r->data);
        m.flip = std::numeric_limits<double>::quiet_NaN();
    }
    return m;
}

std::string toJson(const ImageMetrics& m) {
    std::string s = "{\"layer\": \"" + m.layer + "\", \"channels\": " + std::to_string(m.channels) +
                    ", \"pixels\": " + std::to_string(m.pixels);
    auto add = [&](const char* key, double v) { s += std::string(", \"") + key + "\": " + number(v); };
    add("mse", m.mse);
    add("rmse", m.rmse);
    add("relmse", m.relMse);
    add("relmse_epsilon", kRelMseEpsilon);
    add("mae", m.mae);
    add("psnr", m.psnr);
    add("ssim", m.ssim);
    add("mean_error", m.meanError);
    add("pearson", m.pearson);
    add("flip", m.flip);
    return s + "}";
}

}  // namespace voxgi
