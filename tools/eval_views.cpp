#include "tools/eval_views.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
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

// Keeps the `limit` views with the highest full-image FLIP, with their images.
struct WorstKeeper {
    struct Entry {
        int view;
        double flip;
        Image image;
    };
    std::vector<Entry> entries;
    void offer(int view, double flip, const Image& image, int limit) {
        if (limit <= 0 || (int(entries.size()) >= limit && !(flip > entries.back().flip))) return;
        // The beauty layer alone: all that the images and FLIP maps read.
        Image beauty(image.width(), image.height());
        beauty.layer("beauty") = *image.find("beauty");
        beauty.display = image.display;
        entries.push_back({view, flip, std::move(beauty)});
        std::stable_sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) { return a.flip > b.flip; });
        if (int(entries.size()) > limit) entries.pop_back();
    }
};

std::string runLabel(const std::string& method, const std::string& preset, bool heldOut) {
    return (preset == "default" ? method : method + "-" + preset) + (heldOut ? "-held-out" : "");
}

}  // namespace

ViewsEval evaluateViews(const Scene& scene, const std::string& name, const std::vector<Camera>& views,
                        const ViewsJob& job, const std::string& dir) {
    ViewsEval out;
    out.name = name;
    out.width = scene.camera.width;
    out.height = scene.camera.height;
    out.spp = job.spp;
    out.views = views;
    const std::string folder = name + "/views";
    std::filesystem::create_directories(dir + "/" + folder);

    // Every reference first: they are the slow part, and their progress says how long it takes.
    std::vector<Scene> viewScenes;
    for (const Camera& c : views) {
        viewScenes.push_back(scene);
        viewScenes.back().camera = c;
    }
    double renderedSeconds = 0.0;
    for (std::size_t k = 0; k < views.size(); ++k) {
        const auto start = std::chrono::steady_clock::now();
        const Reference ref = loadOrRenderReference(viewScenes[k], name + "-view" + std::to_string(k), job.spp, job.cacheDir);
        out.referenceSeconds.push_back(ref.seconds);
        if (!ref.fromCache) {
            ++out.referencesRendered;
            renderedSeconds += secondsSince(start);
        }
        // The time left, from the mean of the references rendered so far (cached ones are free).
        const double perView = out.referencesRendered ? renderedSeconds / out.referencesRendered : 0.0;
        std::printf("%s: view %zu/%zu reference %s; about %.0f s of references left\n", name.c_str(), k + 1, views.size(),
                    ref.fromCache ? "from the cache" : "path traced", perView * double(views.size() - k - 1));
        std::fflush(stdout);
    }

    std::vector<WorstKeeper> worst(job.runs.size() + 1);
    std::vector<std::vector<SettingList>> fits(job.runs.size());
    for (const auto& [method, preset] : job.runs) {
        ViewsRow row;
        row.method = method;
        row.preset = preset.name;
        row.settings = settingsText(preset.settings);
        row.oracle = findMethod(method).oracle();
        out.rows.push_back(row);
    }
    const auto score = [&](const Image& image, const Reference& ref, double frameMs) {
        ViewScore s;
        s.full = computeMetrics(image, ref.image, "beauty");
        s.indirect = computeMetrics(image, ref.image, "indirect");
        s.frameMs = frameMs;
        return s;
    };
    for (std::size_t k = 0; k < views.size(); ++k) {
        const Scene& viewScene = viewScenes[k];
        const Reference ref = loadOrRenderReference(viewScene, name + "-view" + std::to_string(k), job.spp, job.cacheDir);
        for (std::size_t r = 0; r < job.runs.size(); ++r) {
            const auto& [method, preset] = job.runs[r];
            std::printf("%s: view %zu/%zu %s...\n", name.c_str(), k + 1, views.size(), runLabel(method, preset.name, false).c_str());
            std::fflush(stdout);
            SettingList fitted;
            if (out.rows[r].oracle) {
                RenderWith render = [&](const SettingList& extra) {
                    return renderMethod(viewScene, method, preset, job.settings, extra).image;
                };
                fitted = findMethod(method).fitToReference(render, ref.image);
            }
            fits[r].push_back(fitted);
            const MethodRun run = renderMethod(viewScene, method, preset, job.settings, fitted);
            ViewScore s = score(run.image, ref, run.frameMs);
            s.fitted = settingsText(fitted);
            out.rows[r].views.push_back(s);
            worst[r].offer(int(k), s.full.flip, run.image, job.worstViews);
        }
    }
    // Oracles held out: each view scored with what the other views' references taught them.
    const std::size_t runs = out.rows.size();
    for (std::size_t r = 0; r < runs && views.size() > 1; ++r) {
        if (!out.rows[r].oracle) continue;
        const auto& [method, preset] = job.runs[r];
        ViewsRow held = out.rows[r];
        held.oracle = false;
        held.heldOut = true;
        held.views.clear();
        for (std::size_t k = 0; k < views.size(); ++k) {
            std::printf("%s: view %zu/%zu %s...\n", name.c_str(), k + 1, views.size(), runLabel(method, preset.name, true).c_str());
            std::fflush(stdout);
            const Reference ref = loadOrRenderReference(viewScenes[k], name + "-view" + std::to_string(k), job.spp, job.cacheDir);
            const SettingList settings = heldOutSettings(fits[r], k);
            const MethodRun run = renderMethod(viewScenes[k], method, preset, job.settings, settings);
            ViewScore s = score(run.image, ref, run.frameMs);
            s.fitted = settingsText(settings);
            held.views.push_back(s);
            worst.back().offer(int(k), s.full.flip, run.image, job.worstViews);
        }
        out.rows.push_back(held);
        break;  // one held-out row: the worst-view keeper has one slot for it
    }

    // The worst views' images, FLIP maps and references.
    std::map<int, std::string> referencePngs;
    for (std::size_t r = 0; r < out.rows.size(); ++r) {
        ViewsRow& row = out.rows[r];
        const WorstKeeper& keeper = r < runs ? worst[r] : worst.back();
        for (const WorstKeeper::Entry& e : keeper.entries) {
            const Reference ref = loadOrRenderReference(viewScenes[std::size_t(e.view)], name + "-view" + std::to_string(e.view),
                                                        job.spp, job.cacheDir);
            const std::string view = "view" + std::to_string(e.view);
            if (!referencePngs.count(e.view)) {
                referencePngs[e.view] = folder + "/" + view + "-reference.png";
                writePng(dir + "/" + referencePngs[e.view], ref.image, "beauty", 0.0f);
            }
            ViewsRow::Worst w;
            w.view = e.view;
            w.flip = e.flip;
            w.referencePng = referencePngs[e.view];
            const std::string stem = folder + "/" + view + "-" + runLabel(row.method, row.preset, row.heldOut);
            w.imagePng = stem + ".png";
            w.flipPng = stem + "-flip.png";
            writePng(dir + "/" + w.imagePng, e.image, "beauty", 0.0f);
            writeFlipMap(dir + "/" + w.flipPng, e.image, ref.image);
            row.worst.push_back(w);
        }
    }
    return out;
}

}  // namespace voxgi::cli
