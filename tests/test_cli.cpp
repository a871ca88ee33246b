// CLI exit codes and messages: help, not-implemented verbs, bad input (exit 2, one line, no
// partial output file), and a successful render.
#include <gtest/gtest.h>

#include "support/test_support.h"

using voxgi::test::fileExists;
using voxgi::test::makeTempDir;
using voxgi::test::runVoxgi;
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
    auto r = runVoxgi("render cornell-box --method isr -o " + dir + "/x.exr");
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
    EXPECT_NE(plan.output.find("reflections: no glossy"), std::string::npos) << plan.output;
}
