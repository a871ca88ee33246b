// voxgi: the command-line front end. Each verb does one thing (like vdb_tool's actions);
// errors print one line and exit 2 (bad input), 3 (not implemented yet) or 1 (failure).
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "gl/context.h"
#include "scenes/atomic_file.h"
#include "scenes/memory_limit.h"
#include "scenes/errors.h"
#include "tools/commands.h"

namespace voxgi::cli {

namespace {
std::map<std::string, Command>& registry() {
    static std::map<std::string, Command> commands;
    return commands;
}

// The verbs of the design, in the order --help lists them.
const std::vector<std::pair<std::string, std::string>> kVerbs = {
    {"voxelize", "voxelize a scene or mesh into sparse OpenVDB geometry volumes"},
    {"inspect", "print the grids of a .vdb file, or slice them to PNG"},
    {"render", "render a scene in real time (GL) with a GI method to EXR/PNG"},
    {"reference", "path-trace the unbiased reference image (Embree)"},
    {"compare", "image error metrics between two EXR files"},
    {"dump", "write a GI method's volumes to .vdb for debugging"},
    {"methods", "list the GI methods, or one method's settings, presets and debug views"},
    {"view", "open the interactive viewer (GLFW window)"},
    {"eval", "error against run time for methods and presets; stability suite"},
    {"bench", "benchmarks (voxelize, propagation, probes, ...)"},
};

void printHelp() {
    std::printf("usage: voxgi <command> [options]\n\ncommands:\n");
    for (const auto& [verb, summary] : kVerbs) std::printf("  %-10s %s\n", verb.c_str(), summary.c_str());
    std::printf("\n`voxgi <command> --help` shows a command's options.\n"
                "`voxgi --max-memory GIB <command> ...` holds its memory estimates to GIB (default: 3/4 of RAM).\n");
}
}  // namespace

bool registerCommand(const Command& command) {
    registry()[command.name] = command;
    return true;
}

const Command* findCommand(const std::string& name) {
    auto it = registry().find(name);
    return it == registry().end() ? nullptr : &it->second;
}

}  // namespace voxgi::cli

int main(int argc, char** argv) {
    using namespace voxgi::cli;
    std::vector<std::string> args(argv + 1, argv + argc);
    // --max-memory GIB before the command: the limit every memory estimate is held to.
    if (args.size() >= 2 && args[0] == "--max-memory") {
        char* end = nullptr;
        const double gib = std::strtod(args[1].c_str(), &end);
        if (end == args[1].c_str() || *end != '\0' || !(gib > 0.0) || gib > 1e6) {
            std::fprintf(stderr, "voxgi: error: --max-memory %s: expected GiB in (0, 1e6]\n", args[1].c_str());
            return kBadInput;
        }
        voxgi::setMemoryLimit(std::uint64_t(gib * 1024.0 * 1024.0 * 1024.0));
        args.erase(args.begin(), args.begin() + 2);
    }
    if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
        printHelp();
        return args.empty() ? kBadInput : kOk;
    }
    if (args[0] == "--version") {
        std::printf("voxgi %s\n", VOXGI_VERSION);
        return kOk;
    }
    const std::string verb = args[0];
    bool known = false;
    for (const auto& v : kVerbs) known = known || v.first == verb;
    const Command* command = findCommand(verb);
    if (!command) {
        if (known) {
            std::fprintf(stderr, "voxgi %s: not implemented yet\n", verb.c_str());
            return kNotImplemented;
        }
        std::fprintf(stderr, "voxgi: unknown command '%s' (see voxgi --help)\n", verb.c_str());
        return kBadInput;
    }
    std::vector<std::string> rest(args.begin() + 1, args.end());
    if (!rest.empty() && (rest[0] == "--help" || rest[0] == "-h")) {
        std::printf("usage: %s\n", command->usage.c_str());
        if (command->details) std::printf("%s", command->details().c_str());
        return kOk;
    }
    try {
        // A command's outputs appear together when it returns, or not at all when it throws.
        voxgi::OutputBatch outputs;
        const int status = command->run(rest);
        outputs.commit();
        return status;
    } catch (const voxgi::InputError& e) {
        std::fprintf(stderr, "voxgi %s: error: %s\n", verb.c_str(), e.what());
        return kBadInput;
    } catch (const voxgi::NotImplementedError& e) {
        std::fprintf(stderr, "voxgi %s: %s\n", verb.c_str(), e.what());
        return kNotImplemented;
    } catch (const voxgi::gl::GlError& e) {
        std::fprintf(stderr, "voxgi %s: error: %s\n", verb.c_str(), e.what());
        return kFailure;
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "voxgi %s: error: out of memory\n", verb.c_str());
        return kFailure;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "voxgi %s: error: %s\n", verb.c_str(), e.what());
        return kFailure;
    }
}
