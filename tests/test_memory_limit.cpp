// Memory estimated before it is allocated: settings or sizes whose estimate exceeds the limit
// (3/4 of RAM, or --max-memory GIB) are exit 2 with the estimate and the limit, at once.
#include <gtest/gtest.h>

#include "scenes/errors.h"
#include "scenes/memory_limit.h"
#include "support/test_support.h"

using namespace voxgi;
using namespace voxgi::test;

TEST(MemoryLimit, EstimatesOverTheLimitAreRefusedBeforeAnyWork) {
    const std::string dir = makeTempDir("memory");
    // 256^3 cells in 5 cascades: tens of GiB, more than this machine or the default limit.
    RunResult lpv = runVoxgi("--max-memory 16 render cornell-box --method clpv --width 32 --height 32 -o " + dir +
                             "/a.exr --set lpv.resolution=256 --set lpv.cascades=5");
    EXPECT_EQ(lpv.exitCode, 2) << lpv.output;
    EXPECT_NE(lpv.output.find("needs about"), std::string::npos) << lpv.output;
    EXPECT_NE(lpv.output.find("the memory limit is 16.0 GiB"), std::string::npos) << lpv.output;
    RunResult image = runVoxgi("--max-memory 0.05 reference cornell-box --spp 1 --width 2048 --height 2048 -o " + dir + "/b.exr");
    EXPECT_EQ(image.exitCode, 2) << image.output;
    EXPECT_NE(image.output.find("path tracer: 2048x2048"), std::string::npos) << image.output;
    // 32^3 probes with 64x64-texel tiles: about 11 GiB of atlases.
    RunResult ddgi = runVoxgi("--max-memory 4 render cornell-box --method ddgi --width 16 --height 16 -o " + dir +
                              "/e.exr --set ddgi.probes=32,32,32 --set ddgi.irradiance_texels=64 --set ddgi.distance_texels=64");
    EXPECT_EQ(ddgi.exitCode, 2) << ddgi.output;
    EXPECT_NE(ddgi.output.find("method ddgi with its gi.ddgi settings needs about"), std::string::npos) << ddgi.output;
    EXPECT_FALSE(fileExists(dir + "/a.exr") || fileExists(dir + "/b.exr") || fileExists(dir + "/e.exr"));
    // Under the limit the same commands run.
    EXPECT_EQ(runVoxgi("--max-memory 0.5 render cornell-box --method clpv --width 16 --height 16 --frames 1 -o " + dir +
                       "/c.exr").exitCode,
              0);
    EXPECT_EQ(runVoxgi("--max-memory zero render cornell-box -o " + dir + "/d.exr").exitCode, 2);
}

// Readers estimate from what a file claims: an EXR's dataWindow (a 1 KB file claimed 3147521x1793
// pixels and the zero-filled layers took 24 GB; found by tests/fuzz/fuzz_exr), and inspect's
// --pixels image of a slice.
TEST(MemoryLimit, ImagesAreEstimatedFromTheirClaimedSize) {
    const std::string dir = makeTempDir("memory-images");
    ASSERT_EQ(runVoxgi("render cornell-box --width 64 --height 64 -o " + dir + "/a.exr").exitCode, 0);
    RunResult exr = runVoxgi("--max-memory 0.00001 compare " + dir + "/a.exr " + dir + "/a.exr");
    EXPECT_EQ(exr.exitCode, 2) << exr.output;
    EXPECT_NE(exr.output.find("a.exr: a 64x64 image needs about"), std::string::npos) << exr.output;
    EXPECT_EQ(runVoxgi("compare " + dir + "/a.exr " + dir + "/a.exr").exitCode, 0);
    ASSERT_EQ(runVoxgi("voxelize cornell-box --voxel-size 0.1 -o " + dir + "/v.vdb").exitCode, 0);
    RunResult png = runVoxgi("--max-memory 0.01 inspect " + dir + "/v.vdb --slice y=0.3 --pixels 4096 -o " + dir + "/s.png");
    EXPECT_EQ(png.exitCode, 2) << png.output;
    EXPECT_NE(png.output.find("image needs about"), std::string::npos) << png.output;
    EXPECT_FALSE(fileExists(dir + "/s.png"));
}

TEST(MemoryLimit, RequireMemoryNamesTheWorkAndTheLimit) {
    const std::uint64_t before = memoryLimit();
    setMemoryLimit(std::uint64_t(1) << 30);
    EXPECT_NO_THROW(requireMemory(0.5 * double(std::uint64_t(1) << 30), "small"));
    try {
        requireMemory(3.0 * double(std::uint64_t(1) << 30), "big thing");
        ADD_FAILURE() << "not refused";
    } catch (const InputError& e) {
        EXPECT_STREQ(e.what(), "big thing needs about 3.0 GiB; the memory limit is 1.0 GiB (--max-memory)");
    }
    setMemoryLimit(before);
}
