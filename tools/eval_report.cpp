#include "tools/eval_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <sstream>

#include <nlohmann/json.hpp>

#include "gi/metrics/flip.h"
#include "scenes/atomic_file.h"
#include "scenes/errors.h"

namespace voxgi::cli {


glm::dvec3 layerMean(const Image& image, const std::string& layer) {
    const ImageLayer* l = image.find(layer);
    if (!l || l->channels != 3) throw InputError("layer " + layer + ": missing or not RGB");
    glm::dvec3 sum(0.0);
    glm::dvec3 count(0.0);
    for (std::size_t i = 0; i < l->data.size(); ++i)
        if (std::isfinite(l->data[i])) {
            sum[int(i % 3)] += l->data[i];
            count[int(i % 3)] += 1.0;
        }
    return sum / glm::max(count, glm::dvec3(1.0));
}

// Error 0 stays black, rising through red and yellow to white at 1 (or above).
void writeFlipMap(const std::string& path, const Image& test, const Image& reference) {
    std::vector<float> e = flip::hdrFlip(test.find("beauty")->data, reference.find("beauty")->data,
                                         reference.width(), reference.height()).error;
    std::vector<std::uint8_t> rgb(3 * e.size());
    for (std::size_t i = 0; i < e.size(); ++i) {
        float v = std::clamp(e[i], 0.0f, 1.0f);
        float c[3] = {std::sqrt(v), v, v * v * v};
        for (int k = 0; k < 3; ++k) rgb[3 * i + std::size_t(k)] = std::uint8_t(std::lround(255.0f * c[k]));
    }
    writePngRgb8(path, reference.width(), reference.height(), rgb);
}

std::string formatNumber(double v, const char* format) {
    if (std::isnan(v)) return "nan";
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    char buf[64];
    std::snprintf(buf, sizeof buf, format, v);
    return buf;
}

bool gnuplotAvailable() { return std::system("gnuplot -e 'exit' >/dev/null 2>&1") == 0; }

std::vector<std::size_t> paretoFront(const std::vector<double>& time, const std::vector<double>& error) {
    std::vector<std::size_t> order(time.size());
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return time[a] != time[b] ? time[a] < time[b] : error[a] < error[b];
    });
    std::vector<std::size_t> front;
    double best = INFINITY;
    for (std::size_t i : order) {
        if (!std::isfinite(error[i]) || !(error[i] < best)) continue;
        best = error[i];
        front.push_back(i);
    }
    return front;
}

namespace {


nlohmann::json metricsJson(const ImageMetrics& m) { return nlohmann::json::parse(toJson(m), nullptr, false); }

std::string label(const EvalRow& r) { return r.preset == "default" ? r.method : r.method + "-" + r.preset; }

// Temporal rows: frames and seconds until the light settled, or the cap they hit.
std::string convergedColumn(const EvalRow& r) {
    if (!r.temporal) return "-";
    return (r.converged ? "" : "no, ") + std::to_string(r.warmupFrames) + " fr, " + formatNumber(r.convergeMs / 1000.0, "%.1f") + " s";
}

// An oracle's row says so: it saw the answer.
std::string methodColumn(const EvalRow& r) { return r.oracle ? r.method + " (oracle fit)" : r.method; }

std::string markdown(const std::vector<SceneEval>& scenes, const ReportInfo& info,
                     const std::vector<std::string>& plots) {
    std::ostringstream md;
    md << "# voxgi eval report\n\n";
    md << "Command: `" << info.command << "`  \nDevice: " << info.device << "\n\n";
    md << "Time is the median wall clock of one frame after the warm-up frames (`renderFrame`, which waits for "
          "the GPU); the image is the average of the frames after the warm-up. Methods whose light builds up over "
          "frames warm up until it settles (`converged`: frames and wall-clock seconds until their light state "
          "changed less than the threshold over their window; `no` when the frame cap came first). Errors are against the path-traced reference on the "
          "full image (beauty) and on the indirect-only layer. FLIP is the mean HDR-FLIP.\n\n";
    if (!info.gnuplot) md << "**Plots skipped: gnuplot was not found** (install `gnuplot-nox`).\n\n";
    for (const SceneEval& s : scenes) {
        md << "## " << s.name << "\n\n";
        md << s.width << "x" << s.height << ", reference: " << s.referenceSpp << " spp path traced" << (s.referenceCaustics ? "" : " without caustics") << " in "
           << formatNumber(s.referenceSeconds, "%.1f") << " s" << (s.referenceCached ? " (reused from cache)" : "")
           << ". Reference against itself: RMSE " << formatNumber(s.selfFull.rmse) << ", FLIP " << formatNumber(s.selfFull.flip)
           << " (full), RMSE " << formatNumber(s.selfIndirect.rmse) << " (indirect).\n\n";
        md << "| method | preset | frame ms | converged | RMSE full | relMSE full | FLIP full | RMSE indirect | relMSE indirect | "
              "FLIP indirect | settings |\n|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---|\n";
        for (const EvalRow& r : s.rows)
            md << "| " << methodColumn(r) << " | " << r.preset << " | " << formatNumber(r.frameMs, "%.1f") << " | "
               << convergedColumn(r) << " | "
               << formatNumber(r.full.rmse) << " | " << formatNumber(r.full.relMse) << " | " << formatNumber(r.full.flip) << " | "
               << formatNumber(r.indirect.rmse) << " | " << formatNumber(r.indirect.relMse) << " | " << formatNumber(r.indirect.flip) << " | "
               << (r.oracle ? "fitted to the reference: " + r.fitted : (r.settings.empty() ? "-" : r.settings))
               << " |\n";
        md << "\nStage medians (GPU ms / CPU ms):\n\n";
        for (const EvalRow& r : s.rows) {
            md << "- " << label(r) << ":";
            for (const auto& [stage, t] : r.stages)
                md << " " << stage << " " << formatNumber(t.gpuMs, "%.2f") << "/" << formatNumber(t.cpuMs, "%.2f");
            md << "\n";
        }
        md << "\n";
        for (const std::string& p : plots)
            if (p.find("plots/" + s.name + "-") == 0) md << "![" << p << "](" << p << ")\n";
        md << "\nReference | images | HDR-FLIP maps (black = no error, white = 1):\n\n";
        md << "![reference](" << s.referencePng << ")";
        for (const EvalRow& r : s.rows) md << " ![" << label(r) << "](" << r.imagePng << ")";
        md << "\n\n";
        for (const EvalRow& r : s.rows) md << " ![" << label(r) << " FLIP](" << r.flipPng << ")";
        md << "\n\nCentre crops, left to right: reference";
        for (const EvalRow& r : s.rows) md << ", " << label(r);
        md << "\n\n![crops](" << s.cropsPng << ")\n\n";
    }
    return md.str();
}

std::string json(const std::vector<SceneEval>& scenes, const ReportInfo& info) {
    nlohmann::json j;
    j["command"] = info.command;
    j["device"] = info.device;
    j["plots"] = info.gnuplot;
    for (const SceneEval& s : scenes) {
        nlohmann::json js{{"name", s.name},
                          {"source", s.source},
                          {"width", s.width},
                          {"height", s.height},
                          {"reference", {{"spp", s.referenceSpp}, {"seconds", s.referenceSeconds},
                                         {"cached", s.referenceCached}, {"path", s.referencePath},
                                         {"caustics", s.referenceCaustics}}},
                          {"reference_mean_indirect", {s.referenceMeanIndirect.x, s.referenceMeanIndirect.y, s.referenceMeanIndirect.z}},
                          {"reference_self", {{"full", metricsJson(s.selfFull)}, {"indirect", metricsJson(s.selfIndirect)}}}};
        for (const EvalRow& r : s.rows) {
            nlohmann::json stages = nlohmann::json::object();
            for (const auto& [stage, t] : r.stages) stages[stage] = {{"gpu_ms", t.gpuMs}, {"cpu_ms", t.cpuMs}};
            nlohmann::json jr{{"method", r.method},         {"preset", r.preset},
                              {"settings", r.settings},     {"frame_ms", r.frameMs},
                              {"frames", r.frames},         {"warmup_frames", r.warmupFrames},
                              {"timed_frames", r.timedFrames}, {"stages", stages},
                              {"temporal", r.temporal},     {"converged", r.converged},
                              {"converge_ms", r.convergeMs},
                              {"full", metricsJson(r.full)}, {"indirect", metricsJson(r.indirect)},
                              {"image", r.imagePng},        {"flip_map", r.flipPng}};
            jr["mean_indirect"] = {r.meanIndirect.x, r.meanIndirect.y, r.meanIndirect.z};
            jr["oracle"] = r.oracle;
            if (r.oracle) jr["fitted"] = r.fitted;
            js["runs"].push_back(jr);
        }
        j["scenes"].push_back(js);
    }
    return j.dump(2) + "\n";
}

std::string csv(const std::vector<SceneEval>& scenes) {
    std::ostringstream c;
    c << "scene,method,preset,frame_ms,rmse_full,relmse_full,flip_full,ssim_full,rmse_indirect,relmse_indirect,"
         "flip_indirect,reference_spp,reference_seconds,warmup_frames,converged,converge_ms\n";
    for (const SceneEval& s : scenes)
        for (const EvalRow& r : s.rows)
            c << s.name << "," << r.method << "," << r.preset << "," << formatNumber(r.frameMs, "%.4f") << ","
              << formatNumber(r.full.rmse, "%.6g") << "," << formatNumber(r.full.relMse, "%.6g") << "," << formatNumber(r.full.flip, "%.6g")
              << "," << formatNumber(r.full.ssim, "%.6g") << "," << formatNumber(r.indirect.rmse, "%.6g") << ","
              << formatNumber(r.indirect.relMse, "%.6g") << "," << formatNumber(r.indirect.flip, "%.6g") << "," << s.referenceSpp << ","
              << formatNumber(s.referenceSeconds, "%.3f") << "," << r.warmupFrames << ","
              << (r.temporal ? (r.converged ? "yes" : "no") : "-") << "," << formatNumber(r.convergeMs, "%.1f") << "\n";
    return c.str();
}

// Two plots per scene: error against time (FLIP full, RMSE indirect), and the Pareto front of
// FLIP full against time. Data and scripts stay next to the PNGs so they can be re-plotted.
std::vector<std::string> plot(const std::string& dir, const SceneEval& s) {
    std::vector<std::string> written;
    std::ostringstream data;
    data << "# label frame_ms flip_full rmse_indirect\n";
    std::vector<double> time, error;
    for (const EvalRow& r : s.rows) {
        data << label(r) << " " << formatNumber(std::max(r.frameMs, 1e-3), "%.6g") << " " << formatNumber(r.full.flip, "%.6g") << " "
             << formatNumber(r.indirect.rmse, "%.6g") << "\n";
        time.push_back(r.frameMs);
        error.push_back(r.full.flip);
    }
    std::ostringstream front;
    for (std::size_t i : paretoFront(time, error))
        front << formatNumber(std::max(time[i], 1e-3), "%.6g") << " " << formatNumber(error[i], "%.6g") << "\n";
    // Paths relative to the report folder, where gnuplot runs, so the folder can move. gnuplot
    // reads its inputs from disk and writes the PNGs itself: these files cannot wait for the
    // command's outputs to be committed together.
    OutputBatch::Immediate plotFiles;
    const std::string base = "plots/" + s.name;
    writeTextAtomically(dir + "/" + base + ".dat", data.str());
    writeTextAtomically(dir + "/" + base + "-pareto.dat", front.str());
    std::ostringstream gp;
    gp << "set terminal png size 900,520\nset logscale x\nset grid\nset key outside right\n"
       << "set xlabel 'frame time (ms, median)'\n"
       << "set output '" << base << "-error-vs-time.png'\n"
       << "set title '" << s.name << ": error against frame time'\nset ylabel 'HDR-FLIP (full image)'\n"
       << "set y2label 'RMSE (indirect layer)'\nset ytics nomirror\nset y2tics\n"
       << "plot '" << base << ".dat' using 2:3 with points pt 7 ps 1.5 title 'HDR-FLIP (full)', \\\n"
       << "     '' using 2:4 axes x1y2 with points pt 5 ps 1.5 title 'RMSE (indirect)', \\\n"
       << "     '' using 2:3:1 with labels offset 0,1 font ',8' notitle\n"
       << "unset y2tics\nunset y2label\nset ytics mirror\n"
       << "set output '" << base << "-pareto.png'\n"
       << "set title '" << s.name << ": Pareto front, methods x presets'\nset ylabel 'HDR-FLIP (full)'\n"
       << "plot '" << base << ".dat' using 2:3 with points pt 7 ps 1.5 title 'method/preset', \\\n"
       << "     '' using 2:3:1 with labels offset 0,1 font ',8' notitle, \\\n"
       << "     '" << base << "-pareto.dat' using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \\\n"
       << "     '" << base << "-pareto.dat' using 1:2 with points pt 6 ps 2.5 lc rgb 'black' notitle\n";
    writeTextAtomically(dir + "/" + base + ".gp", gp.str());
    if (std::system(("cd '" + dir + "' && gnuplot '" + base + ".gp' >/dev/null 2>&1").c_str()) != 0)
        throw InputError(base + ".gp: gnuplot failed");
    written.push_back("plots/" + s.name + "-error-vs-time.png");
    written.push_back("plots/" + s.name + "-pareto.png");
    return written;
}

}  // namespace

std::vector<std::string> writeEvalReport(const std::string& dir, const std::vector<SceneEval>& scenes,
                                         const ReportInfo& info) {
    std::vector<std::string> plots;
    if (info.gnuplot) {
        std::filesystem::create_directories(dir + "/plots");
        for (const SceneEval& s : scenes)
            for (const std::string& p : plot(dir, s)) plots.push_back(p);
    }
    writeTextAtomically(dir + "/report.json", json(scenes, info));
    writeTextAtomically(dir + "/results.csv", csv(scenes));
    writeTextAtomically(dir + "/report.md", markdown(scenes, info, plots));
    return plots;
}

}  // namespace voxgi::cli
