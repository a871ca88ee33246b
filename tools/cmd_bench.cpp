// voxgi bench: dispatches to the benchmarks registered with VOXGI_REGISTER_BENCHMARK.
#include <cstdio>
#include <map>

#include "gi/methods.h"
#include "scenes/errors.h"
#include "tools/bench_registry.h"

namespace voxgi::cli {

namespace {
std::map<std::string, Command>& benchmarks() {
    static std::map<std::string, Command> all;
    return all;
}

std::string list() {
    std::string names;
    for (const auto& [name, b] : benchmarks()) names += (names.empty() ? "" : ", ") + name;
    for (const std::string& m : builtMethods()) names += ", " + m;
    return names;
}

int runBench(const std::vector<std::string>& args) {
    if (args.empty() || args[0] == "--list") {
        for (const auto& [name, b] : benchmarks()) std::printf("%-12s %s\n", name.c_str(), b.usage.c_str());
        for (const MethodInfo& m : methods())
            if (m.built)
                std::printf("%-12s %s\n", m.name.c_str(),
                            m.bench ? "the method's own benchmark: voxgi bench NAME [SCENE...] [--frames N] [--warmup N] "
                                      "[--threads N] [--set k=v]... [--no-gl]"
                                    : "the frame benchmark with this method (voxgi bench frame)");
        if (args.empty()) throw InputError("which benchmark? (" + list() + ")");
        return kOk;
    }
    std::vector<std::string> rest(args.begin() + 1, args.end());
    auto it = benchmarks().find(args[0]);
    if (it == benchmarks().end()) {
        for (const std::string& m : builtMethods())
            if (m == args[0]) return runBenchForMethod(m, rest);
        throw InputError("unknown benchmark '" + args[0] + "' (known: " + list() + ")");
    }
    if (!rest.empty() && (rest[0] == "--help" || rest[0] == "-h")) {
        std::printf("usage: %s\n", it->second.usage.c_str());
        return kOk;
    }
    return it->second.run(rest);
}
}  // namespace

bool registerBenchmark(const Command& benchmark) {
    benchmarks()[benchmark.name] = benchmark;
    return true;
}

VOXGI_REGISTER_COMMAND("bench", "voxgi bench NAME [options] (voxgi bench --list)", runBench);

}  // namespace voxgi::cli
