#include "support/test_support.h"

#include <array>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>
#include <vector>
#include <sys/wait.h>
#include <unistd.h>

#include "gl/context.h"
#include "scenes/scene_loader.h"

namespace voxgi::test {

namespace fs = std::filesystem;

RunResult runVoxgi(const std::string& arguments) {
    return runShell(std::string("\"") + VOXGI_BINARY + "\" " + arguments);
}

RunResult runShell(const std::string& command) {
    RunResult r;
    const std::string cmd = command + " 2>&1";
    FILE* pipe = popen(cmd.c_str(), "r");
    if (!pipe) return r;
    std::array<char, 4096> buf;
    std::size_t n;
    while ((n = fread(buf.data(), 1, buf.size(), pipe)) > 0) r.output.append(buf.data(), n);
    int status = pclose(pipe);
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

namespace {

// The directories a test process made, removed when it exits (VOXGI_KEEP_TEST_DIRS=1 keeps them
// to look at after a failure). Only the thread running the tests makes them.
struct TempDirs {
    std::vector<fs::path> made;
    ~TempDirs() {
        const char* keep = std::getenv("VOXGI_KEEP_TEST_DIRS");
        if (keep && *keep && std::string(keep) != "0") return;
        std::error_code ignored;
        for (const fs::path& dir : made) fs::remove_all(dir, ignored);
    }
};

}  // namespace

std::string makeTempDir(const std::string& tag) {
    static std::atomic<int> counter{0};
    static TempDirs dirs;
    fs::path dir = fs::temp_directory_path() /
                   ("voxgi-test-" + tag + "-" + std::to_string(getpid()) + "-" + std::to_string(counter++));
    fs::remove_all(dir);
    fs::create_directories(dir);
    dirs.made.push_back(dir);
    return dir.string();
}

void writeFile(const std::string& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
}

bool fileExists(const std::string& path) { return fs::exists(path); }

std::string sourcePath(const std::string& relative) { return (fs::path(VOXGI_SOURCE_DIR) / relative).string(); }

std::string sharedScenesDir() {
    const char* env = std::getenv("VOXGI_SCENES");
    fs::path dir = env && *env ? fs::path(env) : fs::path(VOXGI_SHARED_SCENES);
    return fs::is_directory(dir) ? dir.string() : std::string();
}

std::string sharedDataDir(const std::string& name) {
    const char* env = std::getenv("VOXGI_SHARED");
    fs::path dir = (env && *env ? fs::path(env) : fs::path(VOXGI_SHARED_DIR)) / name;
    return fs::is_directory(dir) ? dir.string() : std::string();
}

std::string pythonWith(const std::string& modules) {
    std::vector<std::string> candidates;
    if (const char* env = std::getenv("VOXGI_PYTHON"); env && *env) candidates.push_back(env);
    candidates.insert(candidates.end(), {"python3", "/usr/bin/python3"});
    for (const std::string& py : candidates)
        if (std::system(("\"" + py + "\" -c \"import " + modules + "\" > /dev/null 2>&1").c_str()) == 0) return py;
    return {};
}

Scene cornellBox() { return loadSceneFile(sourcePath("scenes/cornell-box.json")); }

std::vector<glm::ivec3> occupiedVoxels(const SparseGeometryVolume& v, int level) {
    std::vector<glm::ivec3> out;
    IndexBox b = v.indexBounds(level);
    for (int z = b.min.z; z <= b.max.z; ++z)
        for (int y = b.min.y; y <= b.max.y; ++y)
            for (int x = b.min.x; x <= b.max.x; ++x)
                if (v.occupied({x, y, z}, level)) out.push_back({x, y, z});
    return out;
}

void useHeadlessContext() {
    static std::unique_ptr<gl::Context> context = gl::Context::createHeadless();
    context->makeCurrent();
}

}  // namespace voxgi::test
