// voxgi eval --stability on two cases: the table is written, the numbers are the expected ones.
#include <cmath>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/test_support.h"

using namespace voxgi::test;

TEST(EvalStability, TwoCasesWriteTheTable) {
    std::string dir = makeTempDir("eval-stability");
    RunResult r = runVoxgi("eval --stability --cases box-albedo-0.99-pathtrace,bad-geometry-voxelizer -o " + dir);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    ASSERT_TRUE(fileExists(dir + "/stability.md"));
    std::ifstream in(dir + "/stability.json");
    nlohmann::json j = nlohmann::json::parse(in);
    ASSERT_EQ(j["cases"].size(), 2u);
    const auto& box = j["cases"][0];
    EXPECT_EQ(box["name"], "box-albedo-0.99-pathtrace");
    EXPECT_TRUE(box["ran"].get<bool>());
    EXPECT_TRUE(box["finite"].get<bool>());
    // Furnace: L = Le / (1 - albedo) = 100 everywhere.
    EXPECT_NEAR(box["energy_ratio"].get<double>(), 1.0, 0.05);
    EXPECT_GT(box["largest"].get<double>(), 50.0);
    EXPECT_TRUE(box["passed"].get<bool>());
    const auto& vox = j["cases"][1];
    EXPECT_EQ(vox["name"], "bad-geometry-voxelizer");
    EXPECT_EQ(vox["energy_ratio"].get<double>(), 1.0);  // the bad triangles add no voxel
    EXPECT_GE(vox["largest"].get<double>(), 3.0);        // all three were skipped
    EXPECT_TRUE(vox["passed"].get<bool>());
}
