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

// The Cornell box scaled to 0.1 mm: its LPV cells are below OpenVDB's smallest voxel, so the LPV
// voxelizes a copy scaled by a power of two; without it the ordinates had no surfaces and kept
// 0.905 of the unscaled light.
TEST(EvalStability, ATenthOfAMillimetreBoxKeepsItsLpvLight) {
    std::string dir = makeTempDir("eval-stability-small");
    RunResult r = runVoxgi("eval --stability --cases scale-1e-4-lpv -o " + dir);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    std::ifstream in(dir + "/stability.json");
    nlohmann::json j = nlohmann::json::parse(in);
    ASSERT_EQ(j["cases"].size(), 1u);
    EXPECT_NEAR(j["cases"][0]["energy_ratio"].get<double>(), 1.0, 0.01);
    EXPECT_TRUE(j["cases"][0]["passed"].get<bool>());
}
