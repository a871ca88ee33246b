#include "tools/eval_views.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <sstream>

#include "gi/methods.h"
#include "scenes/errors.h"

namespace voxgi::cli {

namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The held-out settings of view `k`: each fitted key's numbers averaged over the other views.
SettingList heldOutSettings(const std::vector<SettingList>& fitted, std::size_t k) {
    std::map<std::string, std::vector<double>> sums;
    std::vector<std::string> order;
    int others = 0;
    for (std::size_t v = 0; v < fitted.size(); ++v) {
        if (v == k) continue;
        ++others;
        for (const auto& [key, value] : fitted[v]) {
            std::istringstream in(value);
            std::vector<double> numbers;
            for (double x; in >> x;) numbers.push_back(x);
            if (!sums.count(key)) order.push_back(key);
            std::vector<double>& s = sums[key];
            s.resize(std::max(s.size(), numbers.size()), 0.0);
            for (std::size_t i = 0; i < numbers.size(); ++i) s[i] += numbers[i];
        }
    }
    SettingList out;
    for (const std::string& key : order) {
        std::ostringstream text;
        text.precision(9);
        const std::vector<double>& s = sums[key];
        for (std::size_t i = 0; i < s.size(); ++i) text << (i ? " " : "") << s[i] / double(std::max(others, 1));
        out.push_back({key, text.str()});
    }
    return out;
}

// The beauty layer alone: all that the worst views' images and FLIP maps read.
Image beautyOf(const Image& image) {
    Image beauty(image.width(), image.height());
    beauty.layer("beauty") = *image.find("beauty");
    beauty.display = image.display;
    return beauty;
}

// Keeps the `limit` views with the highest full-image FLIP, with their images and references.
struct WorstKeeper {
    struct Entry {
        int view;
        double flip;
        Image image, reference;
    };
    std::vector<Entry> entries;
    void offer(int view, double flip, const Image& image, const Image& reference, int limit) {
        if (limit <= 0 || (int(entries.size()) >= limit && !(flip > entries.back().flip))) return;
        entries.push_back({view, flip, beautyOf(image), beautyOf(reference)});
        std::stable_sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) { return a.flip > b.flip; });
        if (int(entries.size()) > limit) entries.pop_back();
    }
};

}  // namespace

ViewsEval evaluateViews(const Scene& scene, const std::string& name, const std::vector<Camera>& views,
                        const ViewsJob& job, const std::string& dir) {
    ViewsEval out;
    out.name = name;
    out.width = scene.camera.width;
    out.height = scene.camera.height;
    out.spp = job.spp;
    out.caustics = job.caustics;
    out.views = views;
    const std::string folder = name + "/views";
    std::filesystem::create_directories(dir + "/" + folder);

    // One copy of the scene, its camera set to the view at hand.
    Scene viewScene = scene;
    auto progress = [&](std::size_t k, const std::string& what) {
        std::printf("%s: view %zu/%zu %s\n", name.c_str(), k + 1, views.size(), what.c_str());
        std::fflush(stdout);
    };

    // Every reference first: they are the slow part, and their progress says how long it takes.
    // They stay in memory (every layer of every view: 100 views at 64x64 are about 30 MB).
    std::vector<Reference> references;
    double renderedSeconds = 0.0;
    for (std::size_t k = 0; k < views.size(); ++k) {
        const auto start = std::chrono::steady_clock::now();
        viewScene.camera = views[k];
        references.push_back(loadOrRenderReference(viewScene, name + "-view" + std::to_string(k), job.spp, job.cacheDir,
                                                    job.caustics));
        const Reference& ref = references.back();
        out.referenceSeconds.push_back(ref.seconds);
        if (!ref.fromCache) {
            ++out.referencesRendered;
            renderedSeconds += secondsSince(start);
        }
        // The time left, from the mean of the references rendered so far (cached ones are free).
        const double perView = out.referencesRendered ? renderedSeconds / out.referencesRendered : 0.0;
        char left[64];
        std::snprintf(left, sizeof left, "%.0f", perView * double(views.size() - k - 1));
        progress(k, std::string("reference ") + (ref.fromCache ? "from the cache" : "path traced") + "; about " + left +
                        " s of references left");
    }

    for (const auto& [method, preset] : job.runs) {
        ViewsRow row;
        row.method = method;
        row.preset = preset.name;
        row.settings = settingsText(preset.settings);
        row.oracle = findMethod(method).oracle();
        out.rows.push_back(row);
    }
    // Per row: its worst views, and an oracle's settings fitted to each view.
    std::vector<WorstKeeper> worst(out.rows.size());
    std::vector<std::vector<SettingList>> fits(out.rows.size());
    auto score = [&](std::size_t r, std::size_t k, const MethodRun& result, const SettingList& settings) {
        ViewScore s;
        s.full = computeMetrics(result.image, references[k].image, "beauty");
        s.indirect = computeMetrics(result.image, references[k].image, "indirect");
        s.frameMs = result.frameMs;
        s.fitted = settingsText(settings);
        out.rows[r].views.push_back(s);
        worst[r].offer(int(k), s.full.flip, result.image, references[k].image, job.worstViews);
    };
    // Row r (of job.runs[run]) with `settings(k)` on every view: an oracle's settings change per
    // view, so it starts afresh each time; any other method keeps one renderer and its light state
    // while the camera moves from view to view.
    auto scoreViews = [&](std::size_t r, std::size_t run, const std::function<SettingList(std::size_t)>& settings) {
        if (views.empty()) return;
        const auto& [method, preset] = job.runs[run];
        viewScene.camera = views.front();  // a session starts where its first view is (DDGI places its probes there)
        const auto session = settings ? nullptr : std::make_unique<MethodSession>(viewScene, method, preset, job.settings);
        for (std::size_t k = 0; k < views.size(); ++k) {
            progress(k, runLabel(out.rows[r]) + "...");
            viewScene.camera = views[k];
            const SettingList s = settings ? settings(k) : SettingList{};
            score(r, k, session ? session->render(views[k]) : renderMethod(viewScene, method, preset, job.settings, s), s);
        }
    };
    for (std::size_t r = 0; r < job.runs.size(); ++r) {
        if (!out.rows[r].oracle) {
            scoreViews(r, r, nullptr);
            continue;
        }
        // Named references, not a structured binding: lambdas may capture those only from C++20.
        const std::string& method = job.runs[r].first;
        const Preset& preset = job.runs[r].second;
        scoreViews(r, r, [&, r](std::size_t k) {
            RenderWith render = [&](const SettingList& extra) {
                return renderMethod(viewScene, method, preset, job.settings, extra).image;
            };
            fits[r].push_back(findMethod(method).fitToReference(render, references[k].image));
            return fits[r].back();
        });
    }
    // Oracles held out: each view scored with what the other views' references taught them.
    for (std::size_t run = 0; run < job.runs.size() && views.size() > 1; ++run) {
        if (!out.rows[run].oracle) continue;
        ViewsRow held = out.rows[run];
        held.oracle = false;
        held.heldOut = true;
        held.views.clear();
        out.rows.push_back(held);
        worst.emplace_back();
        scoreViews(out.rows.size() - 1, run, [&, run](std::size_t k) { return heldOutSettings(fits[run], k); });
    }

    // The worst views' images, FLIP maps and references.
    std::map<int, std::string> referencePngs;
    for (std::size_t r = 0; r < out.rows.size(); ++r) {
        ViewsRow& row = out.rows[r];
        for (const WorstKeeper::Entry& e : worst[r].entries) {
            const std::string view = "view" + std::to_string(e.view);
            if (!referencePngs.count(e.view)) {
                referencePngs[e.view] = folder + "/" + view + "-reference.png";
                writePng(dir + "/" + referencePngs[e.view], e.reference, "beauty", 0.0f);
            }
            ViewsRow::Worst w;
            w.view = e.view;
            w.flip = e.flip;
            w.referencePng = referencePngs[e.view];
            const std::string stem = folder + "/" + view + "-" + runLabel(row);
            w.imagePng = stem + ".png";
            w.flipPng = stem + "-flip.png";
            writePng(dir + "/" + w.imagePng, e.image, "beauty", 0.0f);
            writeFlipMap(dir + "/" + w.flipPng, e.image, e.reference);
            row.worst.push_back(w);
        }
    }
    return out;
}

}  // namespace voxgi::cli
