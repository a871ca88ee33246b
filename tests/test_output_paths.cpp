// Output paths: an output never overwrites an input, a symlink is followed (its target written,
// the link kept), FIFOs and directories are refused before any work, a command's outputs appear
// together or not at all, and an interrupted write leaves no temporary file.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "scenes/atomic_file.h"
#include "scenes/errors.h"
#include "support/test_support.h"

using namespace voxgi;
using namespace voxgi::test;
namespace fs = std::filesystem;

namespace {
std::string readAll(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// Everything in `dir` whose name marks a temporary file.
int temporaries(const std::string& dir) {
    int n = 0;
    for (const auto& e : fs::directory_iterator(dir)) n += e.path().filename().string().find(".tmp") != std::string::npos;
    return n;
}

const std::string kRender = "render cornell-box --method direct --width 16 --height 16 --frames 1 ";
}  // namespace

TEST(OutputPaths, AnOutputThatIsAnInputIsRefusedAndTheInputKept) {
    const std::string dir = makeTempDir("out-input");
    const std::string scene = dir + "/scene.json";
    fs::copy_file(sourcePath("scenes/cornell-box.json"), scene);
    const std::string before = readAll(scene);
    for (const std::string& args : {"render " + scene + " --method direct -o " + scene,
                                    "render " + scene + " --method direct -o " + dir + "/x.exr --png " + scene,
                                    "voxelize " + scene + " --voxel-size 0.1 -o " + scene,
                                    "compare " + dir + "/a.exr " + dir + "/b.exr --regions " + scene + " --json " + scene,
                                    "reference " + scene + " --spp 1 -o " + dir + "/../" + fs::path(dir).filename().string() + "/scene.json"}) {
        RunResult r = runVoxgi(args);
        EXPECT_EQ(r.exitCode, 2) << args << "\n" << r.output;
        EXPECT_NE(r.output.find("is an input of this command"), std::string::npos) << r.output;
        EXPECT_EQ(readAll(scene), before) << args;
    }
    RunResult same = runVoxgi(kRender + "-o " + dir + "/a.exr --png " + dir + "/a.exr");
    EXPECT_EQ(same.exitCode, 2) << same.output;
    EXPECT_FALSE(fileExists(dir + "/a.exr"));
}

TEST(OutputPaths, ASymlinkIsFollowedAndKept) {
    const std::string dir = makeTempDir("out-link");
    fs::create_symlink("target.exr", dir + "/link.exr");
    RunResult r = runVoxgi(kRender + "-o " + dir + "/link.exr");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(fs::is_symlink(dir + "/link.exr"));
    EXPECT_TRUE(fs::is_regular_file(dir + "/target.exr"));
    EXPECT_GT(fs::file_size(dir + "/target.exr"), 100u);
}

TEST(OutputPaths, FifosAndDirectoriesAreRefusedBeforeAnyWork) {
    const std::string dir = makeTempDir("out-fifo");
    ASSERT_EQ(::mkfifo((dir + "/fifo.exr").c_str(), 0644), 0);
    fs::create_directory(dir + "/sub.exr");
    for (const std::string& out : {dir + "/fifo.exr", dir + "/sub.exr"}) {
        RunResult r = runVoxgi(kRender + "-o " + out);
        EXPECT_EQ(r.exitCode, 2) << r.output;
        EXPECT_EQ(r.output.find("rendered"), std::string::npos) << "the render ran: " << r.output;
    }
    EXPECT_TRUE(fs::is_fifo(dir + "/fifo.exr"));
    // Through a symlink too.
    fs::create_symlink("fifo.exr", dir + "/to-fifo.exr");
    EXPECT_EQ(runVoxgi(kRender + "-o " + dir + "/to-fifo.exr").exitCode, 2);
}

TEST(OutputPaths, AnUnwritableDirectoryIsFoundBeforeAnyWork) {
    if (::geteuid() == 0) GTEST_SKIP() << "root writes into read-only directories";
    const std::string dir = makeTempDir("out-ro");
    fs::create_directory(dir + "/ro");
    fs::permissions(dir + "/ro", fs::perms::owner_read | fs::perms::owner_exec);
    RunResult r = runVoxgi(kRender + "-o " + dir + "/a.exr --png " + dir + "/ro/a.png");
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("not writable"), std::string::npos) << r.output;
    EXPECT_FALSE(fileExists(dir + "/a.exr"));
}

TEST(OutputBatch, OutputsAppearTogetherOrNotAtAll) {
    const std::string dir = makeTempDir("batch");
    {
        OutputBatch batch;
        writeTextAtomically(dir + "/first.txt", "one");
        EXPECT_FALSE(fileExists(dir + "/first.txt"));  // not before the commit
        EXPECT_THROW(writeFileAtomically(dir + "/second.txt",
                                         [](const std::string&) { throw std::runtime_error("disk full"); }),
                     InputError);
        // The command fails here: the batch is destroyed without commit.
    }
    EXPECT_FALSE(fileExists(dir + "/first.txt"));
    EXPECT_FALSE(fileExists(dir + "/second.txt"));
    EXPECT_EQ(temporaries(dir), 0);
    {
        OutputBatch batch;
        writeTextAtomically(dir + "/first.txt", "one");
        writeTextAtomically(dir + "/second.txt", "two");
        {
            OutputBatch::Immediate cache;
            writeTextAtomically(dir + "/cache.txt", "kept");
        }
        EXPECT_TRUE(fileExists(dir + "/cache.txt"));
        batch.commit();
    }
    EXPECT_EQ(readAll(dir + "/first.txt"), "one");
    EXPECT_EQ(readAll(dir + "/second.txt"), "two");
    EXPECT_EQ(temporaries(dir), 0);
}

TEST(OutputBatch, AKillDuringAWriteLeavesNoTemporaryFile) {
    const std::string dir = makeTempDir("killed");
    for (int sig : {SIGTERM, SIGINT}) {
        const pid_t child = ::fork();
        ASSERT_GE(child, 0);
        if (child == 0) {
            writeFileAtomically(dir + "/out.bin", [&](const std::string& temporary) {
                std::ofstream(temporary, std::ios::binary) << std::string(1 << 20, 'x');
                ::raise(sig);  // killed half way through the command
            });
            ::_exit(0);
        }
        int status = 0;
        ASSERT_EQ(::waitpid(child, &status, 0), child);
        EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == sig) << "status " << status;
        EXPECT_EQ(temporaries(dir), 0) << "signal " << sig;
        EXPECT_FALSE(fileExists(dir + "/out.bin"));
    }
}
