// `voxgi bench NAME ...`: one benchmark per file, registered like the CLI verbs.
#pragma once

#include "tools/commands.h"

namespace voxgi::cli {

bool registerBenchmark(const Command& benchmark);
// `voxgi bench METHOD`: the method's own benchmark, else the frame benchmark (bench_frame.cpp).
int runBenchForMethod(const std::string& method, const std::vector<std::string>& args);

}  // namespace voxgi::cli

#define VOXGI_REGISTER_BENCHMARK(name, usage, fn) \
    static const bool voxgi_registered_bench_##fn = ::voxgi::cli::registerBenchmark({name, usage, fn})
