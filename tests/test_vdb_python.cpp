// Every .vdb voxgi writes reads whole with pyopenvdb.readAll (Debian python3-openvdb), which
// knows only float, bool and vec3s grids: the voxelized scene, the LPV and CLPV dumps and the
// DDGI dump (whose probe_state was an int32 grid that stopped readAll). Skips without the module.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdio>
#include <string>
#include <vector>

#include "support/test_support.h"

using namespace voxgi;

namespace {

// Runs tests/vdb_read_all.py on `path`: its exit status and output.
test::RunResult readAll(const std::string& python, const std::string& path) {
    test::RunResult r;
    const std::string command =
        "\"" + python + "\" \"" + test::sourcePath("tests/vdb_read_all.py") + "\" \"" + path + "\" 2>&1";
    FILE* pipe = popen(command.c_str(), "r");
    if (!pipe) return r;
    char buf[512];
    while (fgets(buf, sizeof buf, pipe)) r.output += buf;
    const int status = pclose(pipe);
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

}  // namespace

TEST(VdbPython, EveryDumpReadsWholeWithPyopenvdb) {
    const std::string python = test::pythonWith("pyopenvdb");
    if (python.empty()) GTEST_SKIP() << "no python3 with pyopenvdb (Debian python3-openvdb)";
    const std::string dir = test::makeTempDir("vdb-python");
    struct Case {
        std::string arguments, file;
        std::vector<std::string> grids;
    };
    const std::vector<Case> cases = {
        {"voxelize cornell-box --voxel-size 0.05 --levels 2", "geometry.vdb", {"occupancy", "blocker_sh0", "occupancy_L1"}},
        {"dump cornell-box --method lpv --set lpv.resolution=8", "lpv.vdb", {"irradiance_px_L0", "irradiance_nz_L0"}},
        {"dump cornell-box --method clpv --set lpv.resolution=8", "clpv.vdb", {"irradiance_py_L2"}},
        {"dump cornell-box --method lpv --set lpv.resolution=8 --set lpv.transport=sh", "lpv-sh.vdb",
         {"lpv_r_L0_sh0", "blocker_L0_sh0", "albedo_L0"}},
        {"dump cornell-box --method clpv --set lpv.resolution=8 --set lpv.transport=sh", "clpv-sh.vdb",
         {"lpv_r_L2_sh3", "albedo_L2"}},
        {"dump cornell-box --method ddgi --set ddgi.rays=16", "ddgi.vdb",
         {"probe_position", "probe_offset", "probe_state", "probe_irradiance"}},
        {"dump cornell-box --method ddgi --set ddgi.rays=16 --set ddgi.trace=volume --set ddgi.trace_voxels=4",
         "ddgi-volume.vdb", {"probe_irradiance", "trace_normal", "trace_albedo", "trace_surface_offset"}},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.arguments);
        const std::string path = dir + "/" + c.file;
        const test::RunResult made = test::runVoxgi(c.arguments + " -o " + path);
        ASSERT_EQ(made.exitCode, 0) << made.output;
        const test::RunResult read = readAll(python, path);
        EXPECT_EQ(read.exitCode, 0) << read.output;
        for (const std::string& grid : c.grids) EXPECT_NE(read.output.find(grid + " "), std::string::npos) << read.output;
    }
}
