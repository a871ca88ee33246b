// Helpers for voxgi tests: temporary directories, running the voxgi binary, scene locations.
#pragma once

#include <string>

#include <vector>

#include "scenes/scene.h"
#include "volumes/geometry_volume.h"

namespace voxgi::test {

struct RunResult {
    int exitCode = -1;
    std::string output;  // stdout and stderr together
};

// Runs `command` through the shell and captures its output (stderr too) and exit status.
RunResult runShell(const std::string& command);
// Runs `voxgi <arguments>` through the shell and captures its output and exit status.
RunResult runVoxgi(const std::string& arguments);

// A fresh empty directory under the system temp dir, unique per call, removed when the test
// process exits (VOXGI_KEEP_TEST_DIRS=1 keeps it).
std::string makeTempDir(const std::string& tag);
void writeFile(const std::string& path, const std::string& text);
bool fileExists(const std::string& path);

// Path of a file in the source tree ("scenes/cornell-box.json").
std::string sourcePath(const std::string& relative);
// ../shared/scenes, or $VOXGI_SCENES; empty when absent (tests then skip).
std::string sharedScenesDir();
// ../shared/<name> (or $VOXGI_SHARED/<name>), e.g. "metrics-reference"; empty when absent.
std::string sharedDataDir(const std::string& name);

// A python3 that runs `import <modules>` (e.g. "pyopenvdb"): $VOXGI_PYTHON, then python3 on
// the PATH, then Debian's (a pyenv or venv python3 first on the PATH may lack the Debian
// packages); empty when none does (tests then skip).
std::string pythonWith(const std::string& modules);

// The built-in Cornell box.
Scene cornellBox();

// Every occupied voxel of one level, in z, y, x order.
std::vector<glm::ivec3> occupiedVoxels(const SparseGeometryVolume& volume, int level = 0);

// Makes the process's one headless GL 4.5 context current (created on first use).
void useHeadlessContext();

}  // namespace voxgi::test
