// `voxgi eval SCENE --views N | --views cams.json`: every method and preset judged over many
// camera views of a scene (render/view/view_sampler.h), each against its own cached path-traced
// reference, so that no claim rests on the one view someone chose. Per method and preset: the
// mean, spread and median of the errors across views, how often it beats direct light and the
// fitted ambient (an oracle: it saw each view's reference), seed 003's quality function f_q
// (Eq. 21) and gain against direct light on its mean error (Eq. 19), and its worst views.
// The ambient also runs held out: each view gets the mean of the constants fitted to the other
// views, a baseline that never sees the view it is scored on. A method other than an oracle runs
// on one renderer whose camera visits the views in turn (MethodSession): light that builds up over
// frames settles at the first view and every later one starts from that light state.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "gi/method.h"
#include "gi/metrics/image_metrics.h"
#include "scenes/scene.h"
#include "tools/eval_report.h"
#include "tools/eval_run.h"

namespace voxgi::cli {

struct ViewScore {
    ImageMetrics full, indirect;
    double frameMs = 0.0;
    std::string fitted;  // an oracle's settings fitted to this view's reference
};

struct ViewsRow {
    std::string method, preset, settings;
    bool oracle = false;   // fitted to each view's reference
    bool heldOut = false;  // the oracle's constants, fitted to the other views
    std::vector<ViewScore> views;  // one per view, in view order
    struct Worst {
        int view = 0;
        double flip = 0.0;
        std::string imagePng, flipPng, referencePng;  // relative to the report folder
    };
    std::vector<Worst> worst;  // the views with the highest full-image FLIP, worst first
};

struct ViewsEval {
    std::string name, source, viewsFile;  // viewsFile: the views as a viewer script, relative
    int width = 0, height = 0, spp = 0;
    bool caustics = true;  // the references' (ViewsJob::caustics)
    std::vector<Camera> views;
    std::vector<double> referenceSeconds;  // per view: path tracing time (the cache's record)
    int referencesRendered = 0;            // not found in the cache
    std::vector<ViewsRow> rows;
};

struct ViewsJob {
    std::vector<std::pair<std::string, Preset>> runs;  // method and preset, in report order
    RenderSettings settings;
    int spp = 0;
    bool caustics = true;  // the references' (PathTracerOptions::caustics)
    std::string cacheDir;
    int worstViews = 5;
};

// Renders every run on every view (references first, cached in job.cacheDir, with progress and
// an estimate of the time left) and writes the worst views' images under dir/<name>/views/.
ViewsEval evaluateViews(const Scene& scene, const std::string& name, const std::vector<Camera>& views,
                        const ViewsJob& job, const std::string& dir);

// "method-preset" ("method" for a default preset), "-held-out" appended for a held-out row:
// the row's name in file names, plots and the log.
std::string runLabel(const ViewsRow& row);

// Across the views of one row, against the rows of direct light and the fitted ambient when
// given (fractions are NaN without them).
struct ViewSummary {
    int views = 0;
    double relMseMean = 0, relMseSd = 0, relMseMedian = 0;  // full image
    double flipMean = 0, flipSd = 0, flipMedian = 0;        // full image
    double indirectRelMseMean = 0, indirectFlipMean = 0;
    double frameMsMedian = 0;
    double beatsDirectRelMse = 0, beatsDirectFlip = 0;  // fraction of views with a lower error
    double beatsAmbientRelMse = 0, beatsAmbientFlip = 0;
    double qualityMean = 0;  // seed 003 Eq. 21 against direct light on Eq. 19's mean error, mean over views
    double gainMean = 0, gainMedian = 0;  // (delta_direct - delta) / delta_direct on Eq. 19, percent
};
ViewSummary summarize(const ViewsRow& row, const ViewsRow* direct, const ViewsRow* ambientOracle);

// views.md, views.json and views.csv (one line per run and view) under dir, with plots when
// info.gnuplot; returns the plots written.
std::vector<std::string> writeViewsReport(const std::string& dir, const std::vector<ViewsEval>& scenes,
                                          const ReportInfo& info);

}  // namespace voxgi::cli
