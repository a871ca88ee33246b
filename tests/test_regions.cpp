// Scene regions: parsed strictly, and each reference pixel is attributed to the region its
// surface point is in (checked against the materials the path tracer saw there).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "gi/metrics/regions.h"
#include "gi/pathtrace/path_tracer.h"
#include "scenes/errors.h"
#include "scenes/scene_loader.h"
#include "support/test_support.h"

using namespace voxgi;

namespace {

// The Cornell box path-traced small: depth, normal and albedo layers are what regions need.
const Image& smallCornellReference() {
    static const Image image = [] {
        PathTracerOptions o;
        o.width = 48;
        o.height = 48;
        o.maxBounces = 2;
        const Scene scene = test::cornellBox();  // the path tracer keeps a reference to it
        PathTracer pt(scene, o);
        pt.render(4);
        return pt.image();
    }();
    return image;
}

bool near(glm::vec3 a, glm::vec3 b, float tolerance) { return glm::all(glm::lessThan(glm::abs(a - b), glm::vec3(tolerance))); }

std::string sceneWithRegions(const std::string& regions) {
    return R"({"camera": {"eye": [0, 0, 5], "target": [0, 0, 0]}, "regions": )" + regions + "}";
}

}  // namespace

TEST(Regions, EachPixelGoesToTheRegionOfItsSurface) {
    const Scene scene = test::cornellBox();
    ASSERT_FALSE(scene.regions.empty());
    const Image& ref = smallCornellReference();
    const std::vector<int> region = regionOfPixels(ref, scene);
    const ImageLayer& albedo = *ref.find("albedo");
    std::map<std::string, glm::vec3> materials;
    for (const Material& m : scene.materials) materials[m.name] = m.albedo;
    // Pixels on silhouette edges average samples of two surfaces (albedo, depth and normal
    // alike), so a few per region may hold another material's colour.
    std::map<std::string, std::string> materialOf = {{"ceiling", "white"},  {"floor", "white"},
                                                     {"back_wall", "white"}, {"green_wall", "green"},
                                                     {"red_wall", "red"}};
    std::map<std::string, int> count, matching;
    int greenPixels = 0, greenInWall = 0;
    for (std::size_t i = 0; i < region.size(); ++i) {
        const glm::vec3 a(albedo.data[3 * i], albedo.data[3 * i + 1], albedo.data[3 * i + 2]);
        const bool green = near(a, materials["green"], 1e-3f);
        greenPixels += green ? 1 : 0;
        if (region[i] < 0) continue;
        const std::string& name = scene.regions[std::size_t(region[i])].name;
        ++count[name];
        if (materialOf.count(name) && near(a, materials[materialOf[name]], 1e-3f)) ++matching[name];
        if (name == "green_wall" && green) ++greenInWall;
    }
    for (const auto& [name, material] : materialOf) {
        EXPECT_GT(count[name], 20) << name;
        EXPECT_GE(matching[name], count[name] * 9 / 10) << name << " holds pixels of other materials";
    }
    EXPECT_GT(count["block_sides"], 20);
    // And the other way: nearly every visible green pixel is in the green wall's region.
    ASSERT_GT(greenPixels, 50);
    EXPECT_GE(greenInWall, greenPixels * 9 / 10);
}

TEST(Regions, MeansFollowTheTestImageRegionByRegion) {
    const Scene scene = test::cornellBox();
    const Image& ref = smallCornellReference();
    Image test = ref;
    const std::vector<int> region = regionOfPixels(ref, scene);
    std::size_t ceiling = 0;
    while (scene.regions[ceiling].name != "ceiling") ++ceiling;
    ImageLayer& direct = test.layer("direct");
    for (std::size_t i = 0; i < region.size(); ++i)
        if (region[i] == int(ceiling))
            for (int c = 0; c < 3; ++c) direct.data[3 * i + std::size_t(c)] *= 2.0f;
    double ceilingFlip = 0.0, otherFlip = 0.0;
    for (const RegionMean& m : regionMeans(test, ref, scene, "direct")) {
        if (m.pixels == 0) {
            EXPECT_TRUE(std::isnan(m.ratio)) << m.name;
            continue;
        }
        EXPECT_NEAR(m.ratio, m.name == "ceiling" ? 2.0 : 1.0, 1e-9) << m.name;
        // The error is the region's own: only the doubled ceiling has relMSE, and FLIP, whose
        // filters spread a difference a few pixels, is largest there.
        if (m.name == "ceiling") {
            EXPECT_GT(m.relMse, 0.0);
            ceilingFlip = m.flip;
        } else {
            EXPECT_EQ(m.relMse, 0.0) << m.name;
            otherFlip = std::max(otherFlip, m.flip);
        }
    }
    EXPECT_GT(ceilingFlip, otherFlip);
    EXPECT_THROW(regionMeans(test, ref, scene, "no_such_layer"), InputError);
}

TEST(Regions, BadRegionsAreErrorsNamingTheField) {
    auto error = [](const std::string& regions) {
        try {
            parseSceneJson(sceneWithRegions(regions), "s.json");
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(error(R"([{"name": "a", "min": [0, 0, 0], "max": [1, 1, 1], "colour": 1}])").find("s.json: /regions/0/colour: unknown field"), std::string::npos);
    EXPECT_NE(error(R"([{"name": "a", "max": [1, 1, 1]}])").find("/regions/0: missing field 'min'"), std::string::npos);
    EXPECT_NE(error(R"([{"name": "a", "min": [0, 2, 0], "max": [1, 1, 1]}])").find("/regions/0/max: must not be below min"), std::string::npos);
    EXPECT_NE(error(R"([{"min": [0, 0, 0], "max": [1, 1, 1]}])").find("/regions/0/name"), std::string::npos);
    EXPECT_NE(error(R"([{"name": "a", "min": [0, 0, 0], "max": [1, 1, 1]}, {"name": "a", "min": [0, 0, 0], "max": [1, 1, 1]}])")
                  .find("/regions/1/name: a region named 'a' already exists"), std::string::npos);
    EXPECT_NE(error(R"([{"name": "a", "min": [0, 0, 0], "max": [1, 1, 1], "facing": [1e-30, 0, 0]}])").find("/regions/0/facing"), std::string::npos);
    EXPECT_NE(error(R"({"name": "a"})").find("/regions: expected an array"), std::string::npos);
    const Scene ok = parseSceneJson(sceneWithRegions(R"([{"name": "a", "min": [0, 0, 0], "max": [1, 1, 1], "facing": [0, 2, 0]}])"), "s.json");
    ASSERT_EQ(ok.regions.size(), 1u);
    EXPECT_EQ(ok.regions[0].facing, glm::vec3(0, 1, 0));
}
