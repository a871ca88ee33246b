// The writing half of `voxgi eval --views`: views.md, views.json, views.csv and two plots per
// scene (FLIP across views per run; mean FLIP against frame time).
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <numeric>
#include <sstream>

#include <nlohmann/json.hpp>

#include "scenes/atomic_file.h"
#include "scenes/errors.h"
#include "tools/eval_views.h"

namespace voxgi::cli {

namespace {

double mean(const std::vector<double>& v) {
    return v.empty() ? NAN : std::accumulate(v.begin(), v.end(), 0.0) / double(v.size());
}
double standardDeviation(const std::vector<double>& v) {
    if (v.size() < 2) return 0.0;
    const double m = mean(v);
    double s = 0.0;
    for (double x : v) s += (x - m) * (x - m);
    return std::sqrt(s / double(v.size() - 1));
}
double median(std::vector<double> v) {
    if (v.empty()) return NAN;
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}
template <class F>
std::vector<double> each(const ViewsRow& row, F value) {
    std::vector<double> out;
    for (const ViewScore& s : row.views) out.push_back(value(s));
    return out;
}
// The fraction of views in which `row` has a lower value than `other` (NaN without `other`).
template <class F>
double beats(const ViewsRow& row, const ViewsRow* other, F value) {
    if (!other || other == &row || other->views.size() != row.views.size() || row.views.empty()) return NAN;
    int wins = 0;
    for (std::size_t k = 0; k < row.views.size(); ++k) wins += value(row.views[k]) < value(other->views[k]) ? 1 : 0;
    return double(wins) / double(row.views.size());
}

// Whether the row saw the answer, said where its name is.
std::string methodColumn(const ViewsRow& r) {
    if (r.oracle) return r.method + " (oracle fit)";
    if (r.heldOut) return r.method + " (held out)";
    return r.method;
}
const ViewsRow* findRow(const ViewsEval& s, const std::string& method, bool oracle) {
    for (const ViewsRow& r : s.rows)
        if (r.method == method && r.oracle == oracle && !r.heldOut) return &r;
    return nullptr;
}
std::string percent(double fraction) { return std::isnan(fraction) ? "-" : formatNumber(100.0 * fraction, "%.0f") + " %"; }

std::string markdown(const std::vector<ViewsEval>& scenes, const ReportInfo& info, const std::vector<std::string>& plots) {
    std::ostringstream md;
    md << "# voxgi eval over many views\n\n";
    md << "Command: `" << info.command << "`  \nDevice: " << info.device << "\n\n";
    md << "Each method and preset runs on every view, each view against its own path-traced reference. Errors are "
          "on the full image unless marked indirect; mean ± standard deviation (median) across views. `beats direct` "
          "and `beats ambient`: the share of views with a lower relMSE / lower HDR-FLIP than direct light and than the "
          "ambient fitted to that view's reference (an oracle). f_q: seed 003's quality function (Eq. 21) against "
          "direct light on its mean error (Eq. 19), averaged over views (+1: closer in every view); gain: the "
          "relative drop of that mean error against direct light. The held-out ambient uses, in each view, the "
          "mean of the constants fitted to the other views: it never sees the view it is scored on.\n\n";
    if (!info.gnuplot) md << "**Plots skipped: gnuplot was not found** (install `gnuplot-nox`).\n\n";
    for (const ViewsEval& s : scenes) {
        md << "## " << s.name << "\n\n";
        double refSeconds = std::accumulate(s.referenceSeconds.begin(), s.referenceSeconds.end(), 0.0);
        md << s.views.size() << " views (" << s.viewsFile << "), " << s.width << "x" << s.height << ", references "
           << s.spp << " spp" << (s.caustics ? "" : " without caustics") << ": " << formatNumber(refSeconds / double(std::max<std::size_t>(s.views.size(), 1)), "%.1f")
           << " s of path tracing per view (" << s.referencesRendered << " rendered now, the rest from the cache).\n\n";
        md << "| method | preset | relMSE | FLIP | relMSE indirect | FLIP indirect | frame ms | beats direct | "
              "beats ambient | f_q | gain (Eq. 19) |\n|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
        const ViewsRow* direct = findRow(s, "direct", false);
        const ViewsRow* ambient = findRow(s, "ambient", true);
        for (const ViewsRow& r : s.rows) {
            const ViewSummary v = summarize(r, direct, ambient);
            md << "| " << methodColumn(r) << " | " << r.preset << " | " << formatNumber(v.relMseMean) << " ± "
               << formatNumber(v.relMseSd, "%.2g") << " (" << formatNumber(v.relMseMedian) << ") | "
               << formatNumber(v.flipMean) << " ± " << formatNumber(v.flipSd, "%.2g") << " (" << formatNumber(v.flipMedian)
               << ") | " << formatNumber(v.indirectRelMseMean) << " | " << formatNumber(v.indirectFlipMean) << " | "
               << formatNumber(v.frameMsMedian, "%.1f") << " | " << percent(v.beatsDirectRelMse) << " / "
               << percent(v.beatsDirectFlip) << " | " << percent(v.beatsAmbientRelMse) << " / "
               << percent(v.beatsAmbientFlip) << " | " << (std::isnan(v.qualityMean) ? "-" : formatNumber(v.qualityMean, "%+.2f")) << " | "
               << (std::isnan(v.gainMean) ? "-" : formatNumber(v.gainMean, "%.1f") + " % (median " +
                                                      formatNumber(v.gainMedian, "%.1f") + " %)")
               << " |\n";
        }
        md << "\n";
        for (const std::string& p : plots)
            if (p.find("plots/" + s.name + "-views") == 0) md << "![" << p << "](" << p << ")\n";
        md << "\nWorst views by HDR-FLIP (full image): reference | image | FLIP map.\n\n";
        for (const ViewsRow& r : s.rows) {
            md << "- **" << runLabel(r) << "**:";
            for (const ViewsRow::Worst& w : r.worst) md << " view " << w.view << " (" << formatNumber(w.flip, "%.3f") << ")";
            md << "\n\n ";
            for (const ViewsRow::Worst& w : r.worst)
                md << " ![view " << w.view << " reference](" << w.referencePng << ") ![view " << w.view << "](" << w.imagePng
                   << ") ![view " << w.view << " FLIP](" << w.flipPng << ")";
            md << "\n\n";
        }
    }
    return md.str();
}

nlohmann::json metrics(const ImageMetrics& m) {
    return {{"rmse", m.rmse}, {"relmse", m.relMse}, {"flip", m.flip}, {"mean_error", m.meanError}, {"ssim", m.ssim}};
}

std::string json(const std::vector<ViewsEval>& scenes, const ReportInfo& info) {
    nlohmann::json j;
    j["command"] = info.command;
    j["device"] = info.device;
    for (const ViewsEval& s : scenes) {
        nlohmann::json js{{"name", s.name}, {"views_file", s.viewsFile}, {"width", s.width}, {"height", s.height},
                          {"reference_spp", s.spp}, {"reference_caustics", s.caustics},
                          {"reference_seconds", s.referenceSeconds},
                          {"references_rendered", s.referencesRendered}};
        for (const Camera& c : s.views)
            js["views"].push_back({{"eye", {c.eye.x, c.eye.y, c.eye.z}}, {"target", {c.target.x, c.target.y, c.target.z}}});
        const ViewsRow* direct = findRow(s, "direct", false);
        const ViewsRow* ambient = findRow(s, "ambient", true);
        for (const ViewsRow& r : s.rows) {
            const ViewSummary v = summarize(r, direct, ambient);
            nlohmann::json jr{{"method", r.method}, {"preset", r.preset}, {"settings", r.settings}, {"oracle", r.oracle},
                              {"held_out", r.heldOut}};
            jr["summary"] = {{"views", v.views},
                             {"relmse_mean", v.relMseMean}, {"relmse_sd", v.relMseSd}, {"relmse_median", v.relMseMedian},
                             {"flip_mean", v.flipMean}, {"flip_sd", v.flipSd}, {"flip_median", v.flipMedian},
                             {"indirect_relmse_mean", v.indirectRelMseMean}, {"indirect_flip_mean", v.indirectFlipMean},
                             {"frame_ms_median", v.frameMsMedian},
                             {"beats_direct_relmse", v.beatsDirectRelMse}, {"beats_direct_flip", v.beatsDirectFlip},
                             {"beats_ambient_relmse", v.beatsAmbientRelMse}, {"beats_ambient_flip", v.beatsAmbientFlip},
                             {"quality_vs_direct", v.qualityMean}, {"gain_mean_percent", v.gainMean},
                             {"gain_median_percent", v.gainMedian}};
            for (const ViewScore& vs : r.views) {
                nlohmann::json jv{{"full", metrics(vs.full)}, {"indirect", metrics(vs.indirect)}, {"frame_ms", vs.frameMs}};
                if (!vs.fitted.empty()) jv["fitted"] = vs.fitted;
                jr["views"].push_back(jv);
            }
            for (const ViewsRow::Worst& w : r.worst)
                jr["worst"].push_back({{"view", w.view}, {"flip", w.flip}, {"image", w.imagePng}, {"flip_map", w.flipPng},
                                       {"reference", w.referencePng}});
            js["runs"].push_back(jr);
        }
        j["scenes"].push_back(js);
    }
    return j.dump(2) + "\n";
}

std::string csv(const std::vector<ViewsEval>& scenes) {
    std::ostringstream c;
    c << "scene,view,method,preset,oracle,held_out,frame_ms,relmse_full,flip_full,mean_error_full,relmse_indirect,"
         "flip_indirect\n";
    for (const ViewsEval& s : scenes)
        for (const ViewsRow& r : s.rows)
            for (std::size_t k = 0; k < r.views.size(); ++k) {
                const ViewScore& v = r.views[k];
                c << s.name << "," << k << "," << r.method << "," << r.preset << "," << (r.oracle ? 1 : 0) << ","
                  << (r.heldOut ? 1 : 0) << "," << formatNumber(v.frameMs, "%.4f") << ","
                  << formatNumber(v.full.relMse, "%.6g") << "," << formatNumber(v.full.flip, "%.6g") << ","
                  << formatNumber(v.full.meanError, "%.6g") << "," << formatNumber(v.indirect.relMse, "%.6g") << ","
                  << formatNumber(v.indirect.flip, "%.6g") << "\n";
            }
    return c.str();
}

// Per scene: each run's full-image FLIP over its views, sorted (a distribution: how many views
// stay under a given error), and mean FLIP with its spread against frame time.
std::vector<std::string> plot(const std::string& dir, const ViewsEval& s) {
    OutputBatch::Immediate plotFiles;  // gnuplot reads its inputs from disk (eval_report.cpp)
    const std::string base = "plots/" + s.name + "-views";
    std::ostringstream sorted, summary, gp;
    for (const ViewsRow& r : s.rows) {
        std::vector<double> flips = each(r, [](const ViewScore& v) { return v.full.flip; });
        std::sort(flips.begin(), flips.end());
        sorted << "# " << runLabel(r) << "\n";
        for (std::size_t k = 0; k < flips.size(); ++k)
            sorted << formatNumber((double(k) + 0.5) / double(flips.size()), "%.6g") << " " << formatNumber(flips[k], "%.6g") << "\n";
        sorted << "\n\n";
        const ViewSummary v = summarize(r, nullptr, nullptr);
        summary << runLabel(r) << " " << formatNumber(std::max(v.frameMsMedian, 1e-3), "%.6g") << " "
                << formatNumber(v.flipMean, "%.6g") << " " << formatNumber(v.flipSd, "%.6g") << "\n";
    }
    writeTextAtomically(dir + "/" + base + "-sorted.dat", sorted.str());
    writeTextAtomically(dir + "/" + base + "-summary.dat", summary.str());
    gp << "set terminal png size 900,520\nset grid\nset key outside right\n"
       << "set output '" << base << "-distribution.png'\n"
       << "set title '" << s.name << ": HDR-FLIP over " << s.views.size() << " views'\n"
       << "set xlabel 'fraction of views'\nset ylabel 'HDR-FLIP (full image)'\n"
       << "plot";
    for (std::size_t i = 0; i < s.rows.size(); ++i)
        gp << (i ? ", \\\n    " : " ") << "'" << base << "-sorted.dat' index " << i << " using 1:2 with linespoints title '"
           << runLabel(s.rows[i]) << "'";
    gp << "\n"
       << "set output '" << base << "-error-vs-time.png'\nset logscale x\n"
       << "set title '" << s.name << ": mean HDR-FLIP over views against frame time'\n"
       << "set xlabel 'frame time (ms, median over views)'\nset ylabel 'HDR-FLIP (full), mean +- sd'\n"
       << "plot '" << base << "-summary.dat' using 2:3:4 with yerrorbars pt 7 title 'method/preset', \\\n"
       << "     '' using 2:3:1 with labels offset 0,1 font ',8' notitle\n";
    writeTextAtomically(dir + "/" + base + ".gp", gp.str());
    if (std::system(("cd '" + dir + "' && gnuplot '" + base + ".gp' >/dev/null 2>&1").c_str()) != 0)
        throw InputError(base + ".gp: gnuplot failed");
    return {base + "-distribution.png", base + "-error-vs-time.png"};
}

}  // namespace

std::string runLabel(const ViewsRow& r) {
    return (r.preset == "default" ? r.method : r.method + "-" + r.preset) + (r.heldOut ? "-held-out" : "");
}

ViewSummary summarize(const ViewsRow& row, const ViewsRow* direct, const ViewsRow* ambientOracle) {
    ViewSummary v;
    v.views = int(row.views.size());
    const auto relMse = [](const ViewScore& s) { return s.full.relMse; };
    const auto flip = [](const ViewScore& s) { return s.full.flip; };
    const std::vector<double> r = each(row, relMse), f = each(row, flip);
    v.relMseMean = mean(r);
    v.relMseSd = standardDeviation(r);
    v.relMseMedian = median(r);
    v.flipMean = mean(f);
    v.flipSd = standardDeviation(f);
    v.flipMedian = median(f);
    v.indirectRelMseMean = mean(each(row, [](const ViewScore& s) { return s.indirect.relMse; }));
    v.indirectFlipMean = mean(each(row, [](const ViewScore& s) { return s.indirect.flip; }));
    v.frameMsMedian = median(each(row, [](const ViewScore& s) { return s.frameMs; }));
    v.beatsDirectRelMse = beats(row, direct, relMse);
    v.beatsDirectFlip = beats(row, direct, flip);
    v.beatsAmbientRelMse = beats(row, ambientOracle, relMse);
    v.beatsAmbientFlip = beats(row, ambientOracle, flip);
    v.qualityMean = v.gainMean = v.gainMedian = NAN;
    if (direct && direct != &row && direct->views.size() == row.views.size() && !row.views.empty()) {
        std::vector<double> quality, gain;
        for (std::size_t k = 0; k < row.views.size(); ++k) {
            const double mine = row.views[k].full.meanError, theirs = direct->views[k].full.meanError;
            quality.push_back(mine < theirs ? 1.0 : mine > theirs ? -1.0 : 0.0);
            if (theirs > 0.0) gain.push_back(100.0 * (theirs - mine) / theirs);
        }
        v.qualityMean = mean(quality);
        v.gainMean = mean(gain);
        v.gainMedian = median(gain);
    }
    return v;
}

std::vector<std::string> writeViewsReport(const std::string& dir, const std::vector<ViewsEval>& scenes,
                                          const ReportInfo& info) {
    std::vector<std::string> plots;
    if (info.gnuplot) {
        std::filesystem::create_directories(dir + "/plots");
        for (const ViewsEval& s : scenes)
            for (const std::string& p : plot(dir, s)) plots.push_back(p);
    }
    writeTextAtomically(dir + "/views.json", json(scenes, info));
    writeTextAtomically(dir + "/views.csv", csv(scenes));
    writeTextAtomically(dir + "/views.md", markdown(scenes, info, plots));
    return plots;
}

}  // namespace voxgi::cli
