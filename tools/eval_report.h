// The writing half of `voxgi eval`: report.md, report.json, results.csv and gnuplot plots
// (error against frame time per scene, Pareto front across methods and presets).
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "gi/metrics/image_metrics.h"
#include "tools/eval_run.h"

namespace voxgi::cli {

struct EvalRow {
    std::string method, preset, settings;  // settings as "key=value ..."
    double frameMs = 0.0;
    int warmupFrames = 0, timedFrames = 0, frames = 0;
    bool temporal = false, converged = false;  // MethodRun's: warmed up until the light settled
    double convergeMs = 0.0;
    std::vector<std::pair<std::string, StageTiming>> stages;
    ImageMetrics full, indirect;
    bool oracle = false;            // the method saw the reference (its fitted settings below)
    std::string fitted;             // oracle only: the settings fitted to the reference, "key=value ..."
    glm::dvec3 meanIndirect{0.0};    // mean of the indirect layer per colour
    std::string imagePng, flipPng;  // relative to the report folder
};

struct SceneEval {
    std::string name, source;
    int width = 0, height = 0;
    int referenceSpp = 0;
    double referenceSeconds = 0.0;
    bool referenceCached = false;
    bool referenceCaustics = true;  // false: path traced without caustics (--no-caustics)
    std::string referencePath, referencePng, cropsPng;
    glm::dvec3 referenceMeanIndirect{0.0};
    ImageMetrics selfFull, selfIndirect;  // the reference against itself (must be all zero error)
    std::vector<EvalRow> rows;
};

struct ReportInfo {
    std::string command, device;
    bool gnuplot = false;
};

// Writes the files under `dir` (which exists). Plots only when info.gnuplot; the report says
// when they were skipped. Returns the plot files written (relative to `dir`).
std::vector<std::string> writeEvalReport(const std::string& dir, const std::vector<SceneEval>& scenes,
                                         const ReportInfo& info);

// Per-colour mean of an RGB layer (finite values only).
glm::dvec3 layerMean(const Image& image, const std::string& layer);
// The HDR-FLIP map of test's beauty layer against the reference's as a PNG: error 0 black,
// rising through red and yellow to white at 1 (or above).
void writeFlipMap(const std::string& path, const Image& test, const Image& reference);
// printf-formatted, with nan and inf spelled out.
std::string formatNumber(double v, const char* format = "%.4g");
// Whether `gnuplot` runs.
bool gnuplotAvailable();
// Points (x = time, y = error) on the lower-left Pareto front, sorted by time: no other point is
// both faster and more accurate.
std::vector<std::size_t> paretoFront(const std::vector<double>& time, const std::vector<double>& error);

}  // namespace voxgi::cli
