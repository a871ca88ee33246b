// Per-stage timings: GPU time from GL_TIME_ELAPSED queries and CPU wall time, one sample per
// stage and frame (a stage bracketed several times in a frame, once per light say, adds up), and
// summarised as min / median / max for benchmarks and --timings files.
#pragma once

#include <chrono>
#include <map>
#include <string>
#include <vector>

#include <epoxy/gl.h>

namespace voxgi::gl {

struct StageSamples {
    // NaN where the GPU time could not be right: longer than the wall time from the stage's
    // begin to its read-back (llvmpipe returns its clock since boot for a query begun right
    // after a compute dispatch).
    std::vector<double> gpuMs;
    std::vector<double> cpuMs;
};

struct Summary {
    double min = 0, median = 0, max = 0;
};
// Over the finite values: zero without samples, NaN when no sample is finite.
Summary summarize(std::vector<double> values);

class StageTimers {
public:
    StageTimers() = default;
    ~StageTimers();
    StageTimers(const StageTimers&) = delete;
    StageTimers& operator=(const StageTimers&) = delete;

    // Brackets one stage; nested stages are not allowed (GL has one TIME_ELAPSED query active).
    void begin(const std::string& stage);
    void end();
    // Adds a CPU-only stage measured elsewhere (e.g. Embree tracing).
    void addCpu(const std::string& stage, double ms);
    // Ends the frame: waits for outstanding queries and adds one sample per stage that ran.
    void collect();

    const std::map<std::string, StageSamples>& samples() const { return samples_; }
    std::vector<std::string> stageOrder() const { return order_; }
    // {"stages": {"gbuffer": {"gpu_ms": {"min":..,"median":..,"max":..}, "cpu_ms": {...}, "frames": N}}}
    std::string toJson() const;

private:
    struct Pending {
        std::string stage;
        GLuint query;
        double cpuMs;
        std::chrono::steady_clock::time_point begun;
    };
    std::vector<Pending> pending_;
    std::map<std::string, double> pendingCpu_;  // CPU-only stages of the frame
    std::vector<GLuint> freeQueries_;
    std::map<std::string, StageSamples> samples_;
    std::vector<std::string> order_;
    std::string current_;
    GLuint currentQuery_ = 0;
    std::chrono::steady_clock::time_point start_;
};

}  // namespace voxgi::gl
