#include "scenes/sky_model.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <tbb/parallel_for.h>

#include "scenes/errors.h"
#include "scenes/image.h"
#include "shaders/shared/sky.h"

namespace voxgi {

glm::vec3 Sky::radianceAt(glm::vec3 towardSky) const {
    if (!enabled) return glm::vec3(0.0f);
    if (table.empty()) return radiance;
    const shading::SkyTaps t = shading::skyTaps(towardSky, width, height);
    auto at = [&](int x, int y) { return table[std::size_t(y) * std::size_t(width) + std::size_t(x)]; };
    return shading::skyBlend(at(t.texels.x, t.texels.z), at(t.texels.y, t.texels.z), at(t.texels.x, t.texels.w),
                             at(t.texels.y, t.texels.w), t.fraction);
}

void computeMeanRadiance(Sky& sky) {
    if (sky.table.empty()) return;
    glm::dvec3 sum(0.0);
    double weights = 0.0;
    for (int y = 0; y < sky.height; ++y) {
        const double w = std::sin((double(y) + 0.5) * shading::kPiDouble / double(sky.height));
        for (int x = 0; x < sky.width; ++x) sum += w * glm::dvec3(sky.table[std::size_t(y) * std::size_t(sky.width) + std::size_t(x)]);
        weights += w * double(sky.width);
    }
    sky.radiance = glm::vec3(sum / weights);
}

namespace {

constexpr double kPi = shading::kPiDouble;

// Perez et al.'s luminance distribution with Preetham's coefficients for one of Y, x, y.
struct Perez {
    double a, b, c, d, e;
    double operator()(double cosTheta, double gamma, double cosGamma) const {
        return (1.0 + a * std::exp(b / std::max(cosTheta, 1e-4))) * (1.0 + c * std::exp(d * gamma) + e * cosGamma * cosGamma);
    }
};

Perez perezY(double t) { return {0.1787 * t - 1.4630, -0.3554 * t + 0.4275, -0.0227 * t + 5.3251, 0.1206 * t - 2.5771, -0.0670 * t + 0.3703}; }
Perez perezX(double t) { return {-0.0193 * t - 0.2592, -0.0665 * t + 0.0008, -0.0004 * t + 0.2125, -0.0641 * t - 0.8989, -0.0033 * t + 0.0452}; }
Perez perezYc(double t) { return {-0.0167 * t - 0.2608, -0.0950 * t + 0.0092, -0.0079 * t + 0.2102, -0.0441 * t - 1.6537, -0.0109 * t + 0.0529}; }

// Zenith chromaticity: [T^2, T, 1] M [theta^3, theta^2, theta, 1].
double zenithChromaticity(const double m[3][4], double t, double theta) {
    const double tv[3] = {t * t, t, 1.0}, th[4] = {theta * theta * theta, theta * theta, theta, 1.0};
    double sum = 0.0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 4; ++j) sum += tv[i] * m[i][j] * th[j];
    return sum;
}
constexpr double kZenithX[3][4] = {{0.00166, -0.00375, 0.00209, 0.0},
                                   {-0.02903, 0.06377, -0.03202, 0.00394},
                                   {0.11693, -0.21196, 0.06052, 0.25886}};
constexpr double kZenithY[3][4] = {{0.00275, -0.00610, 0.00317, 0.0},
                                   {-0.04214, 0.08970, -0.04153, 0.00516},
                                   {0.15346, -0.26756, 0.06670, 0.26688}};

// CIE xyY (Y in cd/m^2) to linear sRGB (Rec. 709 primaries, D65 white): (1, 1, 1) has Y = 1.
glm::dvec3 xyYToRgb(double x, double y, double lum) {
    if (y <= 0.0) return glm::dvec3(0.0);
    const double X = x * lum / y, Z = (1.0 - x - y) * lum / y;
    return {3.2404542 * X - 1.5371385 * lum - 0.4985314 * Z, -0.9692660 * X + 1.8760108 * lum + 0.0415560 * Z,
            0.0556434 * X - 0.2040259 * lum + 1.0572252 * Z};
}

void validate(const AtmosphereDesc& desc) {
    if (!(desc.turbidity >= kMinTurbidity && desc.turbidity <= kMaxTurbidity))
        throw InputError("atmosphere: turbidity " + std::to_string(desc.turbidity) + " outside the model's range [2, 10]");
    if (!(desc.sunDirection.y < 0.0f))
        throw InputError("atmosphere: the sun is not above the horizon (its light must travel downward)");
}

}  // namespace

glm::vec3 atmosphereRadiance(const AtmosphereDesc& desc, glm::vec3 towardSky) {
    const glm::dvec3 sun = -glm::normalize(glm::dvec3(desc.sunDirection));
    const glm::dvec3 v = glm::normalize(glm::dvec3(towardSky));
    const double t = desc.turbidity;
    const double thetaS = std::acos(std::clamp(sun.y, -1.0, 1.0));
    const double cosGamma = std::clamp(glm::dot(v, sun), -1.0, 1.0), gamma = std::acos(cosGamma);
    const double cosTheta = std::max(v.y, 0.0);
    // Zenith luminance (kcd/m^2) and chromaticity, then each over its Perez distribution
    // relative to the zenith's.
    const double chi = (4.0 / 9.0 - t / 120.0) * (kPi - 2.0 * thetaS);
    const double zenithLum = (4.0453 * t - 4.9710) * std::tan(chi) - 0.2155 * t + 2.4192;
    const double cosThetaS = std::cos(thetaS);
    const Perez py = perezY(t), px = perezX(t), pc = perezYc(t);
    const double lum = 1000.0 * zenithLum * py(cosTheta, gamma, cosGamma) / py(1.0, thetaS, cosThetaS);
    const double x = zenithChromaticity(kZenithX, t, thetaS) * px(cosTheta, gamma, cosGamma) / px(1.0, thetaS, cosThetaS);
    const double y = zenithChromaticity(kZenithY, t, thetaS) * pc(cosTheta, gamma, cosGamma) / pc(1.0, thetaS, cosThetaS);
    const glm::dvec3 rgb = glm::max(xyYToRgb(x, y, std::max(lum, 0.0)), glm::dvec3(0.0));
    return glm::vec3(rgb * (double(desc.sunIrradiance) / kSolarIlluminanceLux));
}

glm::vec3 sunTransmittance(float zenith, float turbidity) {
    // Relative optical air mass (Kasten's fit, as in Preetham et al.'s appendix), Rayleigh
    // extinction and Angstrom's aerosol extinction with alpha = 1.3 and beta from turbidity.
    const double zenithDeg = double(zenith) * 180.0 / kPi;
    const double mass = 1.0 / (std::cos(double(zenith)) + 0.15 * std::pow(std::max(93.885 - zenithDeg, 1e-3), -1.253));
    const double beta = 0.04608 * double(turbidity) - 0.04586;
    const double lambda[3] = {0.612, 0.549, 0.465};  // micrometres
    glm::vec3 out;
    for (int c = 0; c < 3; ++c) {
        const double rayleigh = std::exp(-0.008735 * std::pow(lambda[c], -4.08) * mass);
        const double aerosol = std::exp(-beta * std::pow(lambda[c], -1.3) * mass);
        out[c] = float(rayleigh * aerosol);
    }
    return out;
}

glm::vec3 solarDirection(float latitudeDeg, float day, float hour) {
    const double deg = kPi / 180.0;
    const double declination = -23.44 * deg * std::cos(2.0 * kPi * (double(day) + 10.0) / 365.0);
    const double hourAngle = 15.0 * deg * (double(hour) - 12.0);
    const double lat = double(latitudeDeg) * deg;
    // Toward the sun in (east, up, north).
    const double up = std::sin(lat) * std::sin(declination) + std::cos(lat) * std::cos(declination) * std::cos(hourAngle);
    const double east = -std::cos(declination) * std::sin(hourAngle);
    const double north = std::cos(lat) * std::sin(declination) - std::sin(lat) * std::cos(declination) * std::cos(hourAngle);
    const glm::dvec3 toward(east, up, -north);
    return glm::vec3(-glm::normalize(toward));
}

AtmosphereSky makeAtmosphere(const AtmosphereDesc& desc) {
    validate(desc);
    AtmosphereSky out;
    Sky& sky = out.sky;
    sky.enabled = true;
    sky.type = SkyType::Atmosphere;
    sky.atmosphere = desc;
    sky.width = std::max(desc.width, 8);
    sky.height = std::max(sky.width / 2, 4);
    sky.table.assign(std::size_t(sky.width) * std::size_t(sky.height), glm::vec3(0.0f));
    const glm::vec3 toSun = -glm::normalize(desc.sunDirection);
    out.sunIrradiance = desc.sunIrradiance * sunTransmittance(std::acos(std::clamp(toSun.y, -1.0f, 1.0f)), desc.turbidity);

    // The sky above the horizon, and its irradiance on the ground: rows in parallel (the viewer
    // remakes the table while the sun is dragged), their sums added in order.
    const double cellSolidAngle = (2.0 * kPi / double(sky.width)) * (kPi / double(sky.height));
    std::vector<glm::dvec3> rowOnGround(std::size_t(sky.height), glm::dvec3(0.0));
    tbb::parallel_for(0, sky.height, [&](int y) {
        for (int x = 0; x < sky.width; ++x) {
            const glm::vec3 d = shading::skyDirection(glm::vec2((float(x) + 0.5f) / float(sky.width), (float(y) + 0.5f) / float(sky.height)));
            if (d.y <= 0.0f) continue;
            const glm::vec3 l = atmosphereRadiance(desc, d);
            sky.table[std::size_t(y) * std::size_t(sky.width) + std::size_t(x)] = l;
            rowOnGround[std::size_t(y)] += glm::dvec3(l) * (double(d.y) * cellSolidAngle * std::sqrt(std::max(0.0, 1.0 - double(d.y) * d.y)));
        }
    });
    glm::dvec3 skyOnGround(0.0);
    for (const glm::dvec3& row : rowOnGround) skyOnGround += row;
    // Below the horizon: a diffuse ground of the given albedo under the sun and the sky.
    const glm::vec3 ground = desc.groundAlbedo / float(kPi) * (out.sunIrradiance * toSun.y + glm::vec3(skyOnGround));
    for (int y = 0; y < sky.height; ++y)
        for (int x = 0; x < sky.width; ++x) {
            const glm::vec3 d = shading::skyDirection(glm::vec2((float(x) + 0.5f) / float(sky.width), (float(y) + 0.5f) / float(sky.height)));
            if (d.y <= 0.0f) sky.table[std::size_t(y) * std::size_t(sky.width) + std::size_t(x)] = ground;
        }
    computeMeanRadiance(sky);
    return out;
}

Light* atmosphereSun(Scene& scene) {
    if (!scene.sky.enabled || scene.sky.type != SkyType::Atmosphere) return nullptr;
    for (Light& light : scene.lights)
        if (light.type == LightType::Directional && light.name == kAtmosphereSunName) return &light;
    return nullptr;
}

bool followSun(Scene& scene) {
    Light* sun = atmosphereSun(scene);
    Sky& sky = scene.sky;
    // The loader gives the light the table's own (unit) direction.
    if (!sun || sun->direction == sky.atmosphere.sunDirection || !(glm::length(sun->direction) > 0.0f)) return false;
    AtmosphereDesc desc = sky.atmosphere;
    desc.sunDirection = glm::normalize(sun->direction);
    if (!(desc.sunDirection.y < 0.0f)) return false;
    const int revision = sky.revision;
    AtmosphereSky made = makeAtmosphere(desc);
    sky = std::move(made.sky);
    sky.revision = revision + 1;
    sun->direction = desc.sunDirection;
    sun->emission = made.sunIrradiance;
    return true;
}

Sky loadEnvmap(const std::string& path, float scale) {
    if (!std::filesystem::exists(path)) throw InputError(path + ": environment map not found");
    const Image image = readExr(path);
    const ImageLayer* rgb = image.find("beauty");
    if (!rgb || rgb->channels != 3 || image.width() < 1 || image.height() < 1)
        throw InputError(path + ": environment map has no RGB layer");
    Sky sky;
    sky.enabled = true;
    sky.type = SkyType::Envmap;
    sky.width = image.width();
    sky.height = image.height();
    sky.table.resize(std::size_t(sky.width) * std::size_t(sky.height));
    for (std::size_t i = 0; i < sky.table.size(); ++i) {
        glm::vec3 v(rgb->data[3 * i], rgb->data[3 * i + 1], rgb->data[3 * i + 2]);
        if (!(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z)) || v.x < 0.0f || v.y < 0.0f || v.z < 0.0f)
            throw InputError(path + ": environment map texel " + std::to_string(i) + " is negative or not finite");
        sky.table[i] = v * scale;
    }
    computeMeanRadiance(sky);
    return sky;
}

}  // namespace voxgi
