// The sky (scenes/sky_model.h, shaders/shared/sky.h): the GPU reads the radiance the CPU reads
// at 1000 random directions; the atmosphere's physics (a low sun is red and dim, the sky is blue
// overhead and bright around the sun, the ground under it is Lambertian); the sun's position
// from date and time; the scene format's sky types and their errors; and the path tracer's
// sampling of a tabulated sky against the analytic irradiance of a plane under it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "gi/pathtrace/path_tracer.h"
#include "gl/context.h"
#include "gl/program.h"
#include "gl/scene_gpu.h"
#include "scenes/errors.h"
#include "scenes/image.h"
#include "scenes/primitives.h"
#include "scenes/scene_loader.h"
#include "scenes/sky_model.h"
#include "shaders/shared/constants.h"
#include "shaders/shared/sky.h"
#include "support/test_support.h"

using namespace voxgi;

namespace {

AtmosphereDesc noonSun() {
    AtmosphereDesc a;
    a.sunDirection = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
    a.turbidity = 3.0f;
    a.width = 128;
    return a;
}

// An environment map with a smooth gradient and one bright small patch.
Sky syntheticEnvmap() {
    Sky sky;
    sky.enabled = true;
    sky.type = SkyType::Envmap;
    sky.width = 64;
    sky.height = 32;
    for (int y = 0; y < sky.height; ++y)
        for (int x = 0; x < sky.width; ++x) {
            glm::vec3 v(0.2f + 0.01f * float(x), 0.3f + 0.02f * float(y), 0.5f);
            if (x >= 40 && x < 43 && y >= 8 && y < 10) v = glm::vec3(40.0f, 30.0f, 20.0f);
            sky.table.push_back(v);
        }
    computeMeanRadiance(sky);
    return sky;
}

std::vector<glm::vec3> randomDirections(int count, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<float> n;
    std::vector<glm::vec3> out = {{0, 1, 0}, {0, -1, 0}, {1, 0, 0}, {1, 0, 1e-7f}, {1, 0, -1e-7f}};
    while (int(out.size()) < count) {
        glm::vec3 d(n(rng), n(rng), n(rng));
        if (glm::length(d) > 1e-3f) out.push_back(glm::normalize(d));
    }
    return out;
}

class SkyGpu : public ::testing::Test {
protected:
    static void SetUpTestSuite() { test::useHeadlessContext(); }
};

}  // namespace

TEST_F(SkyGpu, ReadsTheRadianceTheCpuReadsAt1000Directions) {
    const std::vector<glm::vec3> dirs = randomDirections(1000, 7);
    std::vector<glm::vec4> in;
    for (const glm::vec3& d : dirs) in.emplace_back(d, 0.0f);
    Sky constant;
    constant.enabled = true;
    constant.radiance = glm::vec3(0.25f, 0.5f, 1.0f);
    for (const Sky& sky : {makeAtmosphere(noonSun()).sky, syntheticEnvmap(), constant}) {
        gl::Handle table = uploadSkyTexture(sky);
        gl::Handle queries = gl::createBuffer(in.size() * sizeof(glm::vec4), in.data(), 0);
        gl::Handle results = gl::createBuffer(in.size() * sizeof(glm::vec4), nullptr, GL_DYNAMIC_STORAGE_BIT);
        gl::Program program = gl::Program::compute("tests/sky.comp");
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, queries.id());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, results.id());
        glBindTextureUnit(0, table.id());
        program.use();
        program.set("uSkyTable", 0);
        program.set("uCount", int(in.size()));
        glDispatchCompute(GLuint((in.size() + 63) / 64), 1, 1);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        std::vector<glm::vec4> gpu(in.size());
        glGetNamedBufferSubData(results.id(), 0, GLsizeiptr(gpu.size() * sizeof(glm::vec4)), gpu.data());
        const float scale = std::max({sky.radiance.x, sky.radiance.y, sky.radiance.z});
        ASSERT_GT(scale, 0.0f);
        // The same texels and weights, computed by the same float operations in both
        // languages (shaders/shared/sky.h): the bound is 1e-4 of the four texels' spread.
        float worst = 0.0f;  // the largest difference in units of the texels' spread
        for (std::size_t i = 0; i < dirs.size(); ++i) {
            const glm::vec3 cpu = sky.radianceAt(dirs[i]);
            glm::vec3 spread(0.0f);
            if (sky.tabulated()) {
                const shading::SkyTaps t = shading::skyTaps(dirs[i], sky.width, sky.height);
                glm::vec3 lo(1e30f), hi(-1e30f);
                for (int x : {t.texels.x, t.texels.y})
                    for (int y : {t.texels.z, t.texels.w}) {
                        lo = glm::min(lo, sky.table[std::size_t(y * sky.width + x)]);
                        hi = glm::max(hi, sky.table[std::size_t(y * sky.width + x)]);
                    }
                spread = hi - lo;
            }
            for (int k = 0; k < 3; ++k) {
                const float difference = std::abs(gpu[i][k] - cpu[k]);
                if (spread[k] > 0.0f) worst = std::max(worst, difference / spread[k]);
                ASSERT_LE(difference, 1e-4f * spread[k] + 1e-6f * std::max(std::abs(cpu[k]), scale))
                    << "type " << int(sky.type) << " direction " << i << " (" << dirs[i].x << ", " << dirs[i].y << ", "
                    << dirs[i].z << ") channel " << k << ": gpu " << gpu[i][k] << ", cpu " << cpu[k];
            }
        }
        std::printf("sky type %d: largest GPU - CPU difference %.2g of the four texels' spread\n", int(sky.type),
                    double(worst));
    }
}

TEST(SkyTable, TexelCentresReturnTheTexelAndTheSeamWraps) {
    const Sky sky = syntheticEnvmap();
    for (int y : {0, 9, 31})
        for (int x : {0, 41, 63}) {
            const glm::vec3 d = shading::skyDirection(glm::vec2((float(x) + 0.5f) / 64.0f, (float(y) + 0.5f) / 32.0f));
            const glm::vec3 expected = sky.table[std::size_t(y * 64 + x)];
            const glm::vec3 got = sky.radianceAt(d);
            for (int k = 0; k < 3; ++k) EXPECT_NEAR(got[k], expected[k], 1e-4f * expected[k]) << x << ", " << y;
        }
    // Half way across the seam between column 63 and column 0 of row 20.
    const glm::vec3 seam = shading::skyDirection(glm::vec2(0.0f, 20.5f / 32.0f));
    const glm::vec3 mid = 0.5f * (sky.table[20 * 64 + 63] + sky.table[20 * 64]);
    EXPECT_NEAR(sky.radianceAt(seam).x, mid.x, 1e-4f);
}

TEST(Atmosphere, LowSunIsRedderAndDimmer) {
    const glm::vec3 high = sunTransmittance(glm::radians(20.0f), 3.0f);
    const glm::vec3 low = sunTransmittance(glm::radians(85.0f), 3.0f);
    for (int k = 0; k < 3; ++k) {
        EXPECT_GT(high[k], 0.5f);
        EXPECT_LT(low[k], high[k]);
    }
    EXPECT_GT(high.r, high.b);  // blue is scattered most
    EXPECT_LT(low.b / low.r, 0.5f * high.b / high.r);
    // Hazier air lets less through.
    EXPECT_LT(sunTransmittance(glm::radians(20.0f), 8.0f).g, high.g);
    // The scene's sun light comes from the same numbers.
    AtmosphereDesc a = noonSun();
    a.sunIrradiance = 10.0f;
    const AtmosphereSky sky = makeAtmosphere(a);
    const float zenith = std::acos(-a.sunDirection.y);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(sky.sunIrradiance[k], 10.0f * sunTransmittance(zenith, 3.0f)[k], 1e-5f);
}

TEST(Atmosphere, BlueOverheadBrightAroundTheSunLambertianGround) {
    AtmosphereDesc low = noonSun();
    low.sunDirection = -glm::vec3(std::cos(glm::radians(30.0f)), std::sin(glm::radians(30.0f)), 0.0f);
    const glm::vec3 zenith = atmosphereRadiance(low, glm::vec3(0, 1, 0));
    EXPECT_GT(zenith.b, zenith.r);
    // At the sun's elevation (30 degrees): 10 degrees of azimuth from it, and 90.
    auto atAzimuth = [](float degrees) {
        const float c = std::cos(glm::radians(30.0f)), a = glm::radians(degrees);
        return glm::vec3(c * std::cos(a), std::sin(glm::radians(30.0f)), c * std::sin(a));
    };
    EXPECT_GT(atmosphereRadiance(low, atAzimuth(10.0f)).g, 2.0f * atmosphereRadiance(low, atAzimuth(90.0f)).g);
    const AtmosphereDesc a = noonSun();
    const glm::vec3 toSun = -a.sunDirection;
    // Below the horizon: albedo / pi times the sun's and the sky's irradiance on the ground,
    // the sky's integrated here independently on a finer grid.
    const AtmosphereSky sky = makeAtmosphere(a);
    glm::dvec3 skyIrradiance(0.0);
    const int n = 400;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < 2 * n; ++j) {
            const double theta = (i + 0.5) * 0.5 * shading::kPiDouble / n, phi = (j + 0.5) * shading::kPiDouble / n;
            const glm::vec3 d(float(std::sin(theta) * std::cos(phi)), float(std::cos(theta)), float(std::sin(theta) * std::sin(phi)));
            skyIrradiance += glm::dvec3(atmosphereRadiance(a, d)) * std::cos(theta) * std::sin(theta) *
                             (0.5 * shading::kPiDouble / n) * (shading::kPiDouble / n);
        }
    const glm::vec3 ground = sky.sky.radianceAt(glm::vec3(0, -1, 0));
    const glm::vec3 expected = a.groundAlbedo / shading::kPi * (sky.sunIrradiance * toSun.y + glm::vec3(skyIrradiance));
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(ground[k], expected[k], 0.02f * expected[k]);
}

TEST(Atmosphere, SunPositionFromDateAndTime) {
    // Equinox noon at the equator: overhead. At 45 N: 45 degrees up, due south (+z).
    EXPECT_NEAR(solarDirection(0.0f, 80.0f, 12.0f).y, -1.0f, 0.01f);
    const glm::vec3 d = solarDirection(45.0f, 80.0f, 12.0f);
    EXPECT_NEAR(std::asin(-d.y), glm::radians(45.0f), glm::radians(1.0f));
    EXPECT_GT(-d.z, 0.5f);  // toward the sun: south (+z), north being -z
    EXPECT_NEAR(d.x, 0.0f, 0.01f);
    // Morning: the sun in the east (+x), low; midsummer noon at 45 N is higher than midwinter's.
    const glm::vec3 morning = solarDirection(45.0f, 80.0f, 7.0f);
    EXPECT_GT(-morning.x, 0.5f);
    EXPECT_GT(-solarDirection(45.0f, 172.0f, 12.0f).y, -solarDirection(45.0f, 355.0f, 12.0f).y + 0.5f);
}

namespace {
std::string skyScene(const std::string& sky) {
    return R"({"camera": {"eye": [0, 1, 3], "target": [0, 0, 0]}, "materials": {"m": {"albedo": 0.5}},
      "meshes": [{"type": "quad", "material": "m", "corners": [[-1, 0, 1], [1, 0, 1], [1, 0, -1], [-1, 0, -1]]}],
      "sky": )" + sky + "}";
}
std::string errorOf(const std::string& json) {
    try {
        parseSceneJson(json, "s.json");
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}
}  // namespace

TEST(SkySceneFormat, AtmosphereAddsItsSunAndRefusesWhatTheModelCannotDo) {
    const Scene s = parseSceneJson(
        skyScene(R"({"type": "atmosphere", "sun_position": {"latitude": 45, "day": 172, "hour": 9}, "turbidity": 4})"),
        "s.json");
    ASSERT_TRUE(s.sky.enabled);
    EXPECT_EQ(s.sky.type, SkyType::Atmosphere);
    ASSERT_EQ(s.lights.size(), 1u);
    EXPECT_EQ(s.lights[0].type, LightType::Directional);
    EXPECT_EQ(s.lights[0].angularDiameterDegrees, kSunAngularDiameterDegrees);  // the sun's disc: soft shadows
    EXPECT_LT(s.lights[0].direction.y, 0.0f);
    EXPECT_GT(s.lights[0].emission.r, s.lights[0].emission.b);
    const Scene noSun = parseSceneJson(
        skyScene(R"({"type": "atmosphere", "sun_direction": [0, -1, 0.2], "sun_light": false})"), "s.json");
    EXPECT_TRUE(noSun.lights.empty());

    EXPECT_NE(errorOf(skyScene(R"({"type": "atmosphere", "sun_direction": [0, -1, 0], "turbidity": 12})"))
                  .find("s.json: /sky/turbidity: must be in [2, 10]"),
              std::string::npos);
    EXPECT_NE(errorOf(skyScene(R"({"type": "atmosphere", "sun_direction": [0, 1, 0]})"))
                  .find("/sky/sun_direction: the sun is not above the horizon"),
              std::string::npos);
    EXPECT_NE(errorOf(skyScene(R"({"type": "atmosphere", "sun_position": {"latitude": 45, "day": 172, "hour": 23}})"))
                  .find("/sky/sun_position: the sun is not above the horizon"),
              std::string::npos);
    EXPECT_NE(errorOf(skyScene(R"({"type": "atmosphere"})")).find("/sky: give one of"), std::string::npos);
    EXPECT_NE(errorOf(skyScene(R"({"type": "cloudy"})")).find("/sky/type: expected one of"), std::string::npos);
}

// The viewer moves the atmosphere's sun: the table and the sun's colour follow it, counted in
// the sky's revision; a sun at the horizon, outside the model, leaves both as they were.
TEST(Atmosphere, FollowSunRemakesTheSkyForTheMovedSun) {
    Scene s = parseSceneJson(skyScene(R"({"type": "atmosphere", "sun_direction": [0.3, -1, 0.2], "resolution": 64})"),
                             "s.json");
    ASSERT_EQ(s.lights.size(), 1u);
    EXPECT_FALSE(followSun(s));  // the sun is where the table was made for it
    EXPECT_EQ(s.sky.revision, 0);
    s.lights[0].direction = glm::vec3(0.9f, -0.4f, 0.0f);  // lower: a redder, dimmer sun
    ASSERT_TRUE(followSun(s));
    EXPECT_EQ(s.sky.revision, 1);
    AtmosphereDesc expected = s.sky.atmosphere;
    expected.sunDirection = glm::normalize(glm::vec3(0.9f, -0.4f, 0.0f));
    const AtmosphereSky made = makeAtmosphere(expected);
    EXPECT_EQ(s.lights[0].direction, expected.sunDirection);
    EXPECT_EQ(s.lights[0].emission, made.sunIrradiance);
    ASSERT_EQ(s.sky.table.size(), made.sky.table.size());
    for (std::size_t i = 0; i < made.sky.table.size(); ++i) ASSERT_EQ(s.sky.table[i], made.sky.table[i]) << i;
    EXPECT_EQ(s.sky.radiance, made.sky.radiance);
    EXPECT_FALSE(followSun(s));
    // Below the horizon: nothing changes.
    const std::vector<glm::vec3> table = s.sky.table;
    const glm::vec3 emission = s.lights[0].emission;
    s.lights[0].direction = glm::vec3(1.0f, 0.1f, 0.0f);
    EXPECT_FALSE(followSun(s));
    EXPECT_EQ(s.sky.revision, 1);
    EXPECT_EQ(s.sky.table, table);
    EXPECT_EQ(s.lights[0].emission, emission);
    // Without an atmosphere there is nothing to follow.
    Scene constant = parseSceneJson(skyScene(R"({"type": "constant", "radiance": [1, 1, 1]})"), "s.json");
    constant.lights.push_back(s.lights[0]);
    EXPECT_FALSE(followSun(constant));
}

TEST(SkySceneFormat, EnvmapReadsAnExrAndNamesAMissingOne) {
    const std::string dir = test::makeTempDir("sky-envmap");
    const Sky synthetic = syntheticEnvmap();
    Image image(synthetic.width, synthetic.height);
    ImageLayer& rgb = image.layer("beauty");
    for (std::size_t i = 0; i < synthetic.table.size(); ++i)
        for (int k = 0; k < 3; ++k) rgb.data[3 * i + std::size_t(k)] = synthetic.table[i][k];
    writeExr(dir + "/env.exr", image);
    const std::string json = skyScene(R"({"type": "envmap", "path": "env.exr", "scale": 2})");
    std::ofstream(dir + "/scene.json") << json;
    const Scene s = loadSceneFile(dir + "/scene.json");
    ASSERT_TRUE(s.sky.tabulated());
    EXPECT_EQ(s.sky.width, 64);
    EXPECT_FLOAT_EQ(s.sky.table[9 * 64 + 41].r, 80.0f);
    EXPECT_TRUE(s.lights.empty());
    const std::string missing = errorOf(skyScene(R"({"type": "envmap", "path": "absent.exr"})"));
    EXPECT_NE(missing.find("s.json: /sky/path:"), std::string::npos) << missing;
    EXPECT_NE(missing.find("absent.exr"), std::string::npos) << missing;
}

namespace {
// A 2 m diffuse square at the origin facing up, seen from above, under `sky` alone; with
// `emitter`, also a quad light far below it facing down (so next-event samples are split
// between the sky and an emitter that never reaches the square).
Scene planeUnderSky(const Sky& sky, bool emitter) {
    Scene s;
    Material m;
    m.albedo = glm::vec3(0.5f);
    s.materials = {m};
    s.meshes.push_back(makeQuad({glm::vec3(-1, 0, 1), glm::vec3(1, 0, 1), glm::vec3(1, 0, -1), glm::vec3(-1, 0, -1)}, 0));
    s.sky = sky;
    if (emitter) {
        Light q;
        q.type = LightType::Quad;
        q.position = glm::vec3(-0.5f, -5.0f, -0.5f);
        q.edgeU = glm::vec3(1, 0, 0);
        q.edgeV = glm::vec3(0, 0, 1);
        q.emission = glm::vec3(5.0f);
        s.lights.push_back(q);
    }
    s.camera.eye = glm::vec3(0.0f, 3.0f, 0.001f);
    s.camera.target = glm::vec3(0.0f);
    s.camera.fovYDegrees = 20.0f;
    s.camera.width = s.camera.height = 16;
    s.addQuadLightGeometry();
    return s;
}
}  // namespace

TEST(SkyPathTracing, PlaneUnderATabulatedSkyGetsItsIrradiance) {
    // One scattering off the square: L = albedo / pi * E, E the sky's irradiance on an upward
    // plane, integrated from the table (its bilinear lookup) on a fine grid.
    for (const Sky& sky : {syntheticEnvmap(), makeAtmosphere(noonSun()).sky})
        for (bool emitter : {false, true}) {
            glm::dvec3 e(0.0);
            const int n = 256;
            for (int i = 0; i < n; ++i)
                for (int j = 0; j < 4 * n; ++j) {
                    const double theta = (i + 0.5) * 0.5 * shading::kPiDouble / n, phi = (j + 0.5) * 0.5 * shading::kPiDouble / n;
                    const glm::vec3 d(float(std::sin(theta) * std::cos(phi)), float(std::cos(theta)),
                                      float(std::sin(theta) * std::sin(phi)));
                    e += glm::dvec3(sky.radianceAt(d)) * std::cos(theta) * std::sin(theta) * (0.5 * shading::kPiDouble / n) *
                         (0.5 * shading::kPiDouble / n);
                }
            const glm::dvec3 expected = 0.5 / shading::kPiDouble * e;
            PathTracerOptions o;
            o.maxBounces = 1;
            const Scene scene = planeUnderSky(sky, emitter);  // the tracer keeps a reference
            PathTracer tracer(scene, o);
            tracer.render(256);
            const Image image = tracer.image();
            const ImageLayer& direct = *image.find("direct");
            glm::dvec3 mean(0.0);
            for (std::size_t i = 0; i < direct.data.size(); i += 3)
                mean += glm::dvec3(direct.data[i], direct.data[i + 1], direct.data[i + 2]);
            mean /= double(direct.data.size() / 3);
            for (int k = 0; k < 3; ++k)
                EXPECT_NEAR(mean[k], expected[k], 0.01 * expected[k])
                    << "sky type " << int(sky.type) << (emitter ? " with an emitter" : "") << " channel " << k;
        }
}

TEST(SkySceneFormat, ASceneCanExtendAnotherInItsFolder) {
    const std::string dir = test::makeTempDir("scene-extends");
    std::ofstream(dir + "/base.json") << skyScene(R"({"type": "constant", "radiance": 0.5})");
    std::ofstream(dir + "/noon.json")
        << R"({"extends": "base.json", "sky": {"type": "atmosphere", "sun_direction": [0.2, -1, 0.1]}})";
    const Scene noon = loadSceneFile(dir + "/noon.json");
    EXPECT_EQ(noon.sky.type, SkyType::Atmosphere);  // replaced
    EXPECT_EQ(noon.meshes.size(), 1u);               // kept from the base
    EXPECT_EQ(noon.lights.size(), 1u);               // the atmosphere's sun
    std::ofstream(dir + "/loop.json") << R"({"extends": "loop.json"})";
    std::ofstream(dir + "/elsewhere.json") << R"({"extends": "../base.json"})";
    for (const char* name : {"loop.json", "elsewhere.json"}) {
        try {
            loadSceneFile(dir + "/" + name);
            ADD_FAILURE() << name << " loaded";
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find("/extends:"), std::string::npos) << e.what();
        }
    }
}
