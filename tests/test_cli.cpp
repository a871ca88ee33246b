// CLI exit codes and messages: help, not-implemented verbs, bad input (exit 2, one line, no
// partial output file), and a successful render.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "support/test_support.h"

using voxgi::test::fileExists;
using voxgi::test::makeTempDir;
using voxgi::test::runShell;
using voxgi::test::runVoxgi;
using voxgi::test::sourcePath;
using voxgi::test::writeFile;

namespace {
int lineCount(const std::string& s) {
    int n = 0;
    for (char c : s) n += c == '\n';
    return n;
}
}  // namespace

TEST(Cli, HelpListsEveryVerb) {
    auto r = runVoxgi("--help");
    EXPECT_EQ(r.exitCode, 0);
    for (const char* verb : {"voxelize", "inspect", "render", "reference", "dump", "view", "eval", "bench"})
        EXPECT_NE(r.output.find(verb), std::string::npos) << verb;
}

TEST(Cli, UnknownCommandAndOptionAreBadInput) {
    EXPECT_EQ(runVoxgi("frobnicate").exitCode, 2);
    auto r = runVoxgi("render scenes/cornell-box.json --no-such-option -o /tmp/x.exr");
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.output.find("--no-such-option"), std::string::npos);
}

TEST(Cli, PlannedMethodSaysNotImplemented) {
    std::string dir = makeTempDir("cli-method");
    auto r = runVoxgi("render cornell-box --method ilpv -o " + dir + "/x.exr");
    EXPECT_EQ(r.exitCode, 3) << r.output;
    EXPECT_NE(r.output.find("not implemented yet"), std::string::npos) << r.output;
    EXPECT_FALSE(fileExists(dir + "/x.exr"));
    EXPECT_EQ(runVoxgi("render cornell-box --method magic -o " + dir + "/x.exr").exitCode, 2);
}

TEST(Cli, BadSceneFilesExitTwoWithOneLineAndNoOutput) {
    std::string dir = makeTempDir("cli-bad");
    writeFile(dir + "/malformed.json", "{ \"camera\": ");
    writeFile(dir + "/unknown.json", R"({"camera": {"eye": [0,0,1], "target": [0,0,0]}, "colour": 1})");
    writeFile(dir + "/type.json", R"({"camera": {"eye": "here", "target": [0,0,0]}})");
    writeFile(dir + "/mesh.json",
              R"({"camera": {"eye": [0,0,1], "target": [0,0,0]}, "meshes": [{"type": "file", "path": "nope.obj"}]})");
    const char* cases[][2] = {{"/absent.json", "not found"},
                              {"/malformed.json", "malformed JSON"},
                              {"/unknown.json", "/colour"},
                              {"/type.json", "/camera/eye"},
                              {"/mesh.json", "/meshes/0/path"}};
    for (auto& c : cases) {
        auto r = runVoxgi("render " + dir + c[0] + " -o " + dir + "/out.exr --png " + dir + "/out.png");
        EXPECT_EQ(r.exitCode, 2) << c[0] << ": " << r.output;
        EXPECT_EQ(lineCount(r.output), 1) << r.output;
        EXPECT_NE(r.output.find(c[1]), std::string::npos) << r.output;
        EXPECT_NE(r.output.find(dir + c[0]), std::string::npos) << "message names the file: " << r.output;
        EXPECT_FALSE(fileExists(dir + "/out.exr"));
        EXPECT_FALSE(fileExists(dir + "/out.png"));
    }
}

TEST(Cli, BadOptionValuesExitTwo) {
    std::string dir = makeTempDir("cli-values");
    EXPECT_EQ(runVoxgi("render cornell-box -o " + dir + "/a.exr --width -5").exitCode, 2);
    EXPECT_EQ(runVoxgi("render cornell-box -o " + dir + "/a.exr --frames many").exitCode, 2);
    EXPECT_EQ(runVoxgi("render cornell-box -o /nonexistent-dir/a.exr").exitCode, 2);
    EXPECT_EQ(runVoxgi("render cornell-box").exitCode, 2);  // no -o
    // An unknown method is named where it came from: the option or the scene file.
    writeFile(dir + "/gm.json", R"({"camera": {"eye": [0, 0, 3], "target": [0, 0, 0]},
        "materials": {"m": {"albedo": 0.5}}, "meshes": [{"type": "box", "material": "m"}], "gi": {"method": "bogus"}})");
    auto fromScene = runVoxgi("render " + dir + "/gm.json -o " + dir + "/a.exr");
    EXPECT_EQ(fromScene.exitCode, 2) << fromScene.output;
    EXPECT_NE(fromScene.output.find("gm.json: gi.method: bogus: unknown method"), std::string::npos) << fromScene.output;
    auto fromOption = runVoxgi("render cornell-box --method bogus -o " + dir + "/a.exr");
    EXPECT_NE(fromOption.output.find("--method bogus: unknown method"), std::string::npos) << fromOption.output;
    // Usage errors are one line too.
    for (const char* usage : {"render", "render cornell-box", "voxelize", "reference cornell-box --spp 1", "compare a.exr"}) {
        auto r = runVoxgi(usage);
        EXPECT_EQ(r.exitCode, 2) << usage;
        EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << usage << ":\n" << r.output;
    }
    // --set names a declared setting: a typo is not a setting nothing reads.
    for (const char* set : {"bogus.key=1", "lpv.bogus=1"}) {
        auto r = runVoxgi("render cornell-box --method direct --frames 1 -o " + dir + "/a.exr --set " + set);
        EXPECT_EQ(r.exitCode, 2) << r.output;
        EXPECT_NE(r.output.find("unknown setting"), std::string::npos) << r.output;
    }
    // Methods sharing a section range a key differently: lpv.cascades=3 is clpv's.
    EXPECT_EQ(runVoxgi("render cornell-box --method clpv --width 16 --height 16 --frames 1 -o " + dir +
                       "/c.exr --set lpv.cascades=3 --set lpv.resolution=8").exitCode, 0);
    // ... with a value its table accepts, even when the method is not the one rendered.
    for (const char* set : {"lpv.apply_normal_offset=nan", "lpv.steps=inf", "ddgi.probes=nan", "lpv.reuse=maybe"}) {
        auto r = runVoxgi("render cornell-box --method direct --frames 1 -o " + dir + "/a.exr --set " + set);
        EXPECT_EQ(r.exitCode, 2) << set << ": " << r.output;
    }
    EXPECT_FALSE(fileExists(dir + "/a.exr"));
}

TEST(Cli, RenderWritesExrPngAndTimings) {
    std::string dir = makeTempDir("cli-render");
    auto r = runVoxgi("render cornell-box --method direct --width 64 --height 64 --frames 2 -o " + dir +
                      "/c.exr --png " + dir + "/c.png --timings " + dir + "/t.json");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(fileExists(dir + "/c.exr"));
    EXPECT_TRUE(fileExists(dir + "/c.png"));
    EXPECT_TRUE(fileExists(dir + "/t.json"));
    auto plan = runVoxgi("render cornell-box --plan");
    EXPECT_EQ(plan.exitCode, 0);
    EXPECT_NE(plan.output.find("+ gbuffer"), std::string::npos) << plan.output;
    // Only passes that exist are listed (no reflection tracing is built).
    EXPECT_EQ(plan.output.find("reflections"), std::string::npos) << plan.output;
}

// One backend vocabulary: --backend cpu|gl reaches every method that has a back end.
TEST(Cli, BackendOptionWorksForEveryMethod) {
    std::string dir = makeTempDir("cli-backend");
    for (const char* method : {"lpv", "ddgi"})
        for (const char* backend : {"cpu", "gl"}) {
            auto r = runVoxgi(std::string("render cornell-box --method ") + method + " --backend " + backend +
                              " --width 16 --height 16 --frames 1 --set ddgi.rays=16 -o " + dir + "/x.exr");
            EXPECT_EQ(r.exitCode, 0) << method << " " << backend << ": " << r.output;
        }
    auto bad = runVoxgi("render cornell-box --method ddgi --backend gpu -o " + dir + "/y.exr");
    EXPECT_EQ(bad.exitCode, 2) << bad.output;
    EXPECT_NE(bad.output.find("--backend gpu"), std::string::npos) << bad.output;
    EXPECT_FALSE(fileExists(dir + "/y.exr"));
}

// The method list and a method's settings come from its declaration.
TEST(Cli, MethodsListsMethodsAndSettings) {
    auto all = runVoxgi("methods");
    EXPECT_EQ(all.exitCode, 0) << all.output;
    for (const char* m : {"direct", "ambient", "lpv", "clpv", "ddgi", "isr"}) EXPECT_NE(all.output.find(m), std::string::npos) << m;
    auto lpv = runVoxgi("methods clpv");
    EXPECT_EQ(lpv.exitCode, 0) << lpv.output;
    EXPECT_NE(lpv.output.find("lpv.steps"), std::string::npos) << lpv.output;
    EXPECT_NE(lpv.output.find("[0, 100000]"), std::string::npos) << lpv.output;
    auto help = runVoxgi("render --help");
    EXPECT_NE(help.output.find("ddgi.rays=256"), std::string::npos) << help.output;
    EXPECT_EQ(runVoxgi("methods magic").exitCode, 2);
    auto refused = runVoxgi("render cornell-box --method lpv --set lpv.resolution=10 -o /tmp/never.exr");
    EXPECT_EQ(refused.exitCode, 2);
    EXPECT_NE(refused.output.find("gi.lpv.resolution"), std::string::npos) << refused.output;
}

// scripts/bundle.sh: a folder that runs voxgi with none of the machine's libraries but the GPU
// driver's. The CLI runs from it with the bundle's libraries alone, and renders (with this
// machine's GL driver) from the bundle's shaders.
TEST(Cli, BundleRunsWithItsOwnLibrariesAndShaders) {
    if (runShell(std::string("grep -q __asan_init \"") + VOXGI_BINARY + "\"").exitCode == 0)
        GTEST_SKIP() << "a sanitized binary runs with its runtime first, not through a carried loader";
    const std::string dir = makeTempDir("bundle");
    auto r = runShell("\"" + sourcePath("scripts/bundle.sh") + "\" --binary \"" + VOXGI_BINARY +
                            "\" --dir " + dir + "/voxgi");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    r = runShell("VOXGI_BUNDLE_ONLY=1 " + dir + "/voxgi/voxgi methods");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("ddgi"), std::string::npos) << r.output;
    r = runShell(dir + "/voxgi/voxgi render cornell-box --method direct --width 16 --height 16 --frames 1 -o " +
                       dir + "/direct.exr");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(fileExists(dir + "/direct.exr"));
    r = runShell("\"" + sourcePath("scripts/bundle.sh") + "\" --binary " + dir + "/no-such-binary --dir " + dir + "/x");
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_EQ(lineCount(r.output), 1) << r.output;
    std::filesystem::remove_all(dir);
}

TEST(Cli, BenchFrameTakesWidthByHeightSizesAndPrintsGpuTimes) {
    auto r = runVoxgi("bench direct cornell-box --sizes 24x16 --frames 1 --warmup 0");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("  24x16  "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(" direct_light_ms "), std::string::npos) << r.output;
    for (const char* bad : {"--sizes 24x", "--sizes x16", "--sizes 24x4", "--sizes 24x16x2", "--sizes 24y16"}) {
        r = runVoxgi(std::string("bench direct cornell-box --frames 1 ") + bad);
        EXPECT_EQ(r.exitCode, 2) << bad << ": " << r.output;
        EXPECT_EQ(lineCount(r.output), 1) << r.output;
        EXPECT_NE(r.output.find("--sizes"), std::string::npos) << r.output;
    }
}

TEST(Cli, BenchPropagationAndLimitsPrintTheirRatiosAndRejectBadLists) {
    auto r = runVoxgi("bench propagation --resolutions 12,16 --threads 1 --repeats 1 --steps 2");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("Mcell/s"), std::string::npos) << r.output;
    // One row per resolution, with its share of the triad's limit.
    EXPECT_NE(r.output.find("\n   12       1 |"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("\n   16       1 |"), std::string::npos) << r.output;
    r = runVoxgi("bench limits --scenes cornell-box --size 16 --spp 1 --threads 1");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("GB/s"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("cornell-box"), std::string::npos) << r.output;
    for (const char* bad : {"bench propagation --resolutions 4", "bench propagation --threads x",
                            "bench limits --threads -1"}) {
        r = runVoxgi(bad);
        EXPECT_EQ(r.exitCode, 2) << bad << ": " << r.output;
        EXPECT_EQ(lineCount(r.output), 1) << r.output;
        EXPECT_NE(r.output.find("--"), std::string::npos) << r.output;
    }
    // A scene that does not load stops the run before anything is measured.
    r = runVoxgi("bench limits --scenes cornell-box,no-such-scene.json --threads 1");
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_EQ(lineCount(r.output), 1) << r.output;
    EXPECT_NE(r.output.find("no-such-scene.json"), std::string::npos) << r.output;
}
