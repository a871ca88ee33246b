#include "gi/metrics/flip.h"

#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "shaders/shared/constants.h"

namespace voxgi::flip {

namespace {


// sRGB primaries, D65 white (IEC 61966-2-1).
glm::vec3 linearRgbToXyz(glm::vec3 c) {
    return {0.4124564f * c.r + 0.3575761f * c.g + 0.1804375f * c.b,
            0.2126729f * c.r + 0.7151522f * c.g + 0.0721750f * c.b,
            0.0193339f * c.r + 0.1191920f * c.g + 0.9503041f * c.b};
}
glm::vec3 xyzToLinearRgb(glm::vec3 c) {
    return {3.2404542f * c.x - 1.5371385f * c.y - 0.4985314f * c.z,
            -0.9692660f * c.x + 1.8760108f * c.y + 0.0415560f * c.z,
            0.0556434f * c.x - 0.2040259f * c.y + 1.0572252f * c.z};
}
const glm::vec3 kWhite = linearRgbToXyz(glm::vec3(1.0f));

// YyCxCz: CIELAB with the cube root dropped, linear in XYZ, so it can be filtered.
glm::vec3 xyzToYCxCz(glm::vec3 xyz) {
    glm::vec3 n = xyz / kWhite;
    return {116.0f * n.y - 16.0f, 500.0f * (n.x - n.y), 200.0f * (n.y - n.z)};
}
glm::vec3 yCxCzToXyz(glm::vec3 v) {
    float y = (v.x + 16.0f) / 116.0f;
    return glm::vec3(v.y / 500.0f + y, y, y - v.z / 200.0f) * kWhite;
}

float labF(float t) {
    const float d = 6.0f / 29.0f;
    return t > d * d * d ? std::cbrt(t) : t / (3.0f * d * d) + 4.0f / 29.0f;
}
glm::vec3 xyzToLab(glm::vec3 xyz) {
    glm::vec3 n = xyz / kWhite;
    float fx = labF(n.x), fy = labF(n.y), fz = labF(n.z);
    return {116.0f * fy - 16.0f, 500.0f * (fx - fy), 200.0f * (fy - fz)};
}

// Hunt effect: chroma appears weaker at low lightness.
glm::vec3 hunt(glm::vec3 lab) { return {lab.x, 0.01f * lab.x * lab.y, 0.01f * lab.x * lab.z}; }
float hyab(glm::vec3 a, glm::vec3 b) {
    return std::abs(a.x - b.x) + std::sqrt((a.y - b.y) * (a.y - b.y) + (a.z - b.z) * (a.z - b.z));
}

// Clamp-to-edge separable convolution of one float plane.
void convolveRows(const std::vector<float>& in, std::vector<float>& out, int w, int h, const std::vector<float>& k) {
    int r = int(k.size() / 2);
    tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y != rows.end(); ++y)
            for (int x = 0; x < w; ++x) {
                float s = 0.0f;
                for (int i = -r; i <= r; ++i)
                    s += k[std::size_t(i + r)] * in[std::size_t(y) * w + std::size_t(std::clamp(x + i, 0, w - 1))];
                out[std::size_t(y) * w + std::size_t(x)] = s;
            }
    });
}
void convolveColumns(const std::vector<float>& in, std::vector<float>& out, int w, int h, const std::vector<float>& k) {
    int r = int(k.size() / 2);
    tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y != rows.end(); ++y)
            for (int x = 0; x < w; ++x) {
                float s = 0.0f;
                for (int i = -r; i <= r; ++i)
                    s += k[std::size_t(i + r)] * in[std::size_t(std::clamp(y + i, 0, h - 1)) * w + std::size_t(x)];
                out[std::size_t(y) * w + std::size_t(x)] = s;
            }
    });
}
std::vector<float> separable(const std::vector<float>& in, int w, int h, const std::vector<float>& kx,
                             const std::vector<float>& ky) {
    std::vector<float> tmp(in.size()), out(in.size());
    convolveRows(in, tmp, w, h, kx);
    convolveColumns(tmp, out, w, h, ky);
    return out;
}

// The contrast sensitivity functions of the three opponent channels as sums of Gaussians in
// the spatial domain, s(r) = sum a sqrt(pi / b) exp(-pi^2 r^2 / b), r in degrees (FLIP Sec. 4.1).
struct CsfTerm {
    double a, b;
};
const std::vector<CsfTerm> kCsf[3] = {
    {{1.0, 0.0047}},                  // achromatic
    {{1.0, 0.0053}},                  // red-green
    {{34.1, 0.04}, {13.5, 0.025}},    // blue-yellow
};

// Filters one channel with its CSF; each Gaussian term is separable, the sum is normalised to 1.
std::vector<float> csfFilter(const std::vector<float>& plane, int w, int h, int channel, double ppd) {
    const int radius = int(std::ceil(3.0 * std::sqrt(0.04 / (2.0 * shading::kPiDouble * shading::kPiDouble)) * ppd));
    std::vector<float> out(plane.size(), 0.0f);
    double total = 0.0;
    std::vector<std::vector<float>> kernels;
    std::vector<double> amplitudes;
    for (const CsfTerm& t : kCsf[channel]) {
        std::vector<float> k(std::size_t(2 * radius + 1));
        double sum = 0.0;
        for (int i = -radius; i <= radius; ++i) {
            double x = double(i) / ppd;
            k[std::size_t(i + radius)] = float(std::exp(-shading::kPiDouble * shading::kPiDouble * x * x / t.b));
            sum += k[std::size_t(i + radius)];
        }
        double amplitude = t.a * std::sqrt(shading::kPiDouble / t.b);
        total += amplitude * sum * sum;
        kernels.push_back(std::move(k));
        amplitudes.push_back(amplitude);
    }
    for (std::size_t i = 0; i < kernels.size(); ++i) {
        std::vector<float> f = separable(plane, w, h, kernels[i], kernels[i]);
        float weight = float(amplitudes[i] / total);
        for (std::size_t p = 0; p < out.size(); ++p) out[p] += weight * f[p];
    }
    return out;
}

// Feature detection kernels (FLIP Sec. 4.2): first and second derivatives of a Gaussian of
// standard deviation 0.5 * 0.082 degrees, positive and negative lobes each normalised to +-1.
struct FeatureKernels {
    std::vector<float> gauss, first, second;
};
FeatureKernels featureKernels(double ppd) {
    double sigma = 0.5 * 0.082 * ppd;
    int radius = int(std::ceil(3.0 * sigma));
    FeatureKernels k;
    double gsum = 0.0, pos1 = 0.0, pos2 = 0.0, neg2 = 0.0;
    for (int i = -radius; i <= radius; ++i) {
        double x = double(i), g = std::exp(-x * x / (2.0 * sigma * sigma));
        double d1 = -x * g, d2 = (x * x / (sigma * sigma) - 1.0) * g;
        k.gauss.push_back(float(g));
        k.first.push_back(float(d1));
        k.second.push_back(float(d2));
        gsum += g;
        if (d1 > 0) pos1 += d1;
        (d2 > 0 ? pos2 : neg2) += d2;
    }
    for (std::size_t i = 0; i < k.gauss.size(); ++i) {
        k.gauss[i] = float(k.gauss[i] / gsum);
        k.first[i] = float(k.first[i] / pos1);
        k.second[i] = float(k.second[i] > 0 ? k.second[i] / pos2 : k.second[i] / -neg2);
    }
    return k;
}

struct Features {
    std::vector<float> edge, point;
};
Features detectFeatures(const std::vector<float>& luma, int w, int h, const FeatureKernels& k) {
    std::vector<float> ex = separable(luma, w, h, k.first, k.gauss);
    std::vector<float> ey = separable(luma, w, h, k.gauss, k.first);
    std::vector<float> px = separable(luma, w, h, k.second, k.gauss);
    std::vector<float> py = separable(luma, w, h, k.gauss, k.second);
    Features f;
    f.edge.resize(luma.size());
    f.point.resize(luma.size());
    for (std::size_t i = 0; i < luma.size(); ++i) {
        f.edge[i] = std::sqrt(ex[i] * ex[i] + ey[i] * ey[i]);
        f.point[i] = std::sqrt(px[i] * px[i] + py[i] * py[i]);
    }
    return f;
}

struct Prepared {
    std::vector<float> lab;       // Hunt-adjusted L*a*b* after CSF filtering, 3 per pixel
    std::vector<float> luma;      // normalised achromatic channel for the feature detectors
};
Prepared prepare(const std::vector<float>& rgb, int w, int h, double ppd) {
    std::size_t n = std::size_t(w) * std::size_t(h);
    std::vector<float> planes[3];
    for (auto& p : planes) p.resize(n);
    Prepared out;
    out.luma.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        glm::vec3 c = glm::clamp(glm::vec3(rgb[3 * i], rgb[3 * i + 1], rgb[3 * i + 2]), 0.0f, 1.0f);
        glm::vec3 v = xyzToYCxCz(linearRgbToXyz(c));
        for (int k = 0; k < 3; ++k) planes[k][i] = v[k];
        out.luma[i] = (v.x + 16.0f) / 116.0f;
    }
    for (int k = 0; k < 3; ++k) planes[k] = csfFilter(planes[k], w, h, k, ppd);
    out.lab.resize(3 * n);
    for (std::size_t i = 0; i < n; ++i) {
        glm::vec3 rgbFiltered = glm::clamp(xyzToLinearRgb(yCxCzToXyz({planes[0][i], planes[1][i], planes[2][i]})), 0.0f, 1.0f);
        glm::vec3 lab = hunt(xyzToLab(linearRgbToXyz(rgbFiltered)));
        for (int k = 0; k < 3; ++k) out.lab[3 * i + std::size_t(k)] = lab[k];
    }
    return out;
}

}  // namespace

std::vector<float> ldrFlip(const std::vector<float>& test, const std::vector<float>& reference, int w, int h,
                           const Options& options) {
    const double ppd = options.pixelsPerDegree;
    Prepared t = prepare(test, w, h, ppd), r = prepare(reference, w, h, ppd);
    FeatureKernels kernels = featureKernels(ppd);
    Features ft = detectFeatures(t.luma, w, h, kernels), fr = detectFeatures(r.luma, w, h, kernels);

    // Colour error: HyAB distance, compressed (exponent 0.7) and remapped so that the distance
    // between pure green and pure blue, the largest in the gamut, maps to 1.
    const float qc = 0.7f, pc = 0.4f, pt = 0.95f, qf = 0.5f;
    float cmax = std::pow(hyab(hunt(xyzToLab(linearRgbToXyz({0, 1, 0}))), hunt(xyzToLab(linearRgbToXyz({0, 0, 1})))), qc);
    std::vector<float> error(std::size_t(w) * std::size_t(h));
    for (std::size_t i = 0; i < error.size(); ++i) {
        glm::vec3 a(t.lab[3 * i], t.lab[3 * i + 1], t.lab[3 * i + 2]);
        glm::vec3 b(r.lab[3 * i], r.lab[3 * i + 1], r.lab[3 * i + 2]);
        float dc = std::pow(hyab(a, b), qc);
        float ec = dc < pc * cmax ? pt / (pc * cmax) * dc : pt + (dc - pc * cmax) / (cmax - pc * cmax) * (1.0f - pt);
        float df = std::max(std::abs(ft.edge[i] - fr.edge[i]), std::abs(ft.point[i] - fr.point[i]));
        float ef = std::pow(std::min(df / std::sqrt(2.0f), 1.0f), qf);
        error[i] = std::pow(std::clamp(ec, 0.0f, 1.0f), 1.0f - ef);
    }
    return error;
}

float acesToneMap(float x) {
    // Narkowicz's fit evaluated at 0.6 x, written as one rational function.
    const float a = 0.6f * 0.6f * 2.51f, b = 0.6f * 0.03f, c = 0.6f * 0.6f * 2.43f, d = 0.6f * 0.59f, e = 0.14f;
    x = std::max(x, 0.0f);
    return std::clamp((a * x * x + b * x) / (c * x * x + d * x + e), 0.0f, 1.0f);
}

void exposureRange(const std::vector<float>& reference, double& start, double& stop, int& count) {
    std::vector<float> luminance;
    luminance.reserve(reference.size() / 3);
    float maxLum = 0.0f;
    for (std::size_t i = 0; i + 2 < reference.size(); i += 3) {
        float y = 0.2126f * reference[i] + 0.7152f * reference[i + 1] + 0.0722f * reference[i + 2];
        maxLum = std::max(maxLum, y);
        luminance.push_back(y);
    }
    start = stop = 0.0;
    count = 2;
    if (luminance.empty() || !(maxLum > 0.0f)) return;
    // The input that the tone curve maps to 0.85: solve (a - yc) x^2 + (b - yd) x - ye = 0.
    const double a = 0.6 * 0.6 * 2.51, b = 0.6 * 0.03, c = 0.6 * 0.6 * 2.43, d = 0.6 * 0.59, e = 0.14, y = 0.85;
    double qa = a - y * c, qb = b - y * d, qc = -y * e;
    double x85 = (-qb + std::sqrt(qb * qb - 4.0 * qa * qc)) / (2.0 * qa);
    // The median over all pixels (element n/2), as NVIDIA's FLIP takes it: black background
    // pixels count (leaving them out moved the mean FLIP by ~5e-4 on the metrics-reference
    // images). When that median is black, the median of the lit pixels keeps the range finite.
    auto median = [](std::vector<float>& v) {
        std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
        return double(v[v.size() / 2]);
    };
    double mid = median(luminance);
    if (!(mid > 0.0)) {
        luminance.erase(std::remove_if(luminance.begin(), luminance.end(), [](float v) { return !(v > 0.0f); }),
                        luminance.end());
        mid = median(luminance);
    }
    start = std::log2(x85 / double(maxLum));
    stop = std::log2(x85 / mid);
    count = std::max(2, int(std::ceil(stop - start)));
}

HdrResult hdrFlip(const std::vector<float>& test, const std::vector<float>& reference, int w, int h,
                  const Options& options) {
    HdrResult result;
    exposureRange(reference, result.startExposure, result.stopExposure, result.exposures);
    result.error.assign(std::size_t(w) * std::size_t(h), 0.0f);
    std::vector<float> t(test.size()), r(reference.size());
    for (int i = 0; i < result.exposures; ++i) {
        double c = result.startExposure + (result.stopExposure - result.startExposure) * i / (result.exposures - 1);
        float scale = float(std::exp2(c));
        for (std::size_t k = 0; k < test.size(); ++k) {
            t[k] = acesToneMap(scale * test[k]);
            r[k] = acesToneMap(scale * reference[k]);
        }
        std::vector<float> e = ldrFlip(t, r, w, h, options);
        for (std::size_t p = 0; p < e.size(); ++p) result.error[p] = std::max(result.error[p], e[p]);
    }
    double sum = 0.0;
    for (float e : result.error) sum += e;
    result.mean = result.error.empty() ? 0.0 : sum / double(result.error.size());
    return result;
}

}  // namespace voxgi::flip
