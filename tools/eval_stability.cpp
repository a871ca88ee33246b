#include "tools/eval_stability.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <memory>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "gi/pathtrace/path_tracer.h"
#include "gi/methods.h"
#include "gl/context.h"
#include "render/frame/frame_renderer.h"
#include "scenes/atomic_file.h"
#include "scenes/errors.h"
#include "scenes/primitives.h"
#include "scenes/scene_loader.h"
#include "tools/eval_report.h"
#include "volumes/geometry_volume.h"

namespace voxgi::cli {

namespace {

constexpr double kNoRatio = std::numeric_limits<double>::quiet_NaN();

struct Measured {
    bool finite = true;
    double largest = 0.0;
    double mean = 0.0;
};

Measured measure(const Image& image, std::uint64_t droppedSamples = 0) {
    Measured m;
    const ImageLayer& b = *image.find("beauty");
    double sum = 0.0;
    for (float v : b.data) {
        if (!std::isfinite(v)) {
            m.finite = false;
            continue;
        }
        m.largest = std::max(m.largest, double(std::abs(v)));
        sum += v;
    }
    m.mean = b.data.empty() ? 0.0 : sum / double(b.data.size());
    // The path tracer drops NaN/Inf samples before they reach the image; a dropped one still
    // means the computation blew up.
    if (droppedSamples > 0) m.finite = false;
    return m;
}

Measured pathTrace(const Scene& scene, int spp) {
    PathTracer tracer(scene, PathTracerOptions{});
    tracer.render(spp);
    return measure(tracer.image(), tracer.droppedSamples());
}

gl::Context& glContext() {
    static std::unique_ptr<gl::Context> context = gl::Context::createHeadless();
    return *context;
}

Measured rasterize(const Scene& base, const std::string& method, const SettingList& settings, int frames) {
    glContext();
    Scene scene = base;
    for (const auto& [k, v] : settings) scene.gi.set(k, v);
    FrameRenderer renderer(scene, FrameOptions{}, method);
    for (int f = 0; f < frames; ++f) renderer.renderFrame();
    return measure(renderer.resolve());
}

Scene smallCamera(Scene s, int size) {
    s.camera.width = size;
    s.camera.height = size;
    return s;
}

Scene cornell(int size) { return smallCamera(loadSceneFile(builtinScenePath("cornell-box")), size); }

// A closed 2 m box seen from its centre. With `furnaceEmission` > 0 every wall emits and there is
// no light; otherwise a 1 W/sr point light hangs above the centre.
Scene closedBox(float albedo, float furnaceEmission, int size) {
    Scene s;
    Material m;
    m.name = "wall";
    m.albedo = glm::vec3(albedo);
    m.emission = glm::vec3(furnaceEmission);
    s.materials.push_back(m);
    s.meshes.push_back(makeBox(glm::scale(glm::mat4(1.0f), glm::vec3(2.0f)), 0, true));
    s.camera.eye = glm::vec3(0.0f, 0.0f, -0.5f);
    s.camera.target = glm::vec3(0.0f, 0.0f, 1.0f);
    s.camera.fovYDegrees = 70.0f;
    if (furnaceEmission <= 0.0f) {
        Light l;
        l.type = LightType::Point;
        l.position = glm::vec3(0.2f, 0.5f, 0.3f);
        l.emission = glm::vec3(1.0f);
        s.lights.push_back(l);
    }
    return smallCamera(s, size);
}

// The scene scaled by k about the origin, then moved by `offset` (the same in x, y and z).
Scene placed(Scene s, float k, float offset = 0.0f) {
    auto place = [&](glm::vec3 p) { return p * k + glm::vec3(offset); };
    for (Mesh& m : s.meshes)
        for (glm::vec3& p : m.positions) p = place(p);
    s.camera.eye = place(s.camera.eye);
    s.camera.target = place(s.camera.target);
    s.camera.nearPlane *= k;
    s.camera.farPlane *= k;
    for (Light& l : s.lights) {
        l.position = place(l.position);
        l.edgeU *= k;
        l.edgeV *= k;
    }
    return s;
}

Scene brighter(Scene s, float k) {
    for (Light& l : s.lights) l.emission *= k;
    for (Material& m : s.materials) m.emission *= k;
    return s;
}

// A repeated-vertex triangle, a collinear (zero-area) one and one with a NaN vertex, inside the box.
Scene withBadGeometry(Scene s) {
    Mesh bad;
    bad.name = "bad";
    const float nan = std::numeric_limits<float>::quiet_NaN();
    bad.positions = {{0.2f, 0.2f, 0.2f}, {0.2f, 0.2f, 0.2f}, {0.3f, 0.2f, 0.2f},  // repeated vertex
                     {0.1f, 0.1f, 0.3f}, {0.2f, 0.2f, 0.3f}, {0.3f, 0.3f, 0.3f},  // collinear
                     {0.2f, 0.3f, 0.2f}, {nan, 0.3f, 0.25f}, {0.3f, 0.35f, 0.2f}};
    bad.indices = {0, 1, 2, 3, 4, 5, 6, 7, 8};
    bad.materialIds = {0, 0, 0};
    s.meshes.push_back(bad);
    return s;
}

Scene grazing(Scene s) {
    s.lights.clear();
    s.meshes.erase(std::remove_if(s.meshes.begin(), s.meshes.end(),
                                  [](const Mesh& m) { return m.name.find("light") != std::string::npos; }),
                   s.meshes.end());
    Light sun;
    sun.type = LightType::Directional;
    // 0.057 degrees above the floor's plane, through the open front.
    sun.direction = glm::normalize(glm::vec3(0.0f, -1e-3f, 1.0f));
    sun.emission = glm::vec3(1000.0f);
    s.lights.push_back(sun);
    return s;
}

struct Case {
    std::string name, method, description;
    std::function<void(StabilityResult&)> run;
};

void finish(StabilityResult& r, const Measured& m, double ratio, const std::string& expected, double tolerance) {
    r.finite = m.finite;
    r.largest = m.largest;
    r.ratio = ratio;
    r.expected = expected;
    r.passed = m.finite && (std::isnan(ratio) || std::abs(ratio - 1.0) <= tolerance);
    if (!expected.empty() && std::isnan(ratio)) r.passed = false;  // a comparison that came out NaN
}

double ratioOf(double a, double b) { return b != 0.0 ? a / b : kNoRatio; }

// The real-time cases every method runs (linearity in the light, scale invariance, bad
// triangles, grazing light), then the method's own stiff cases (gi/method.h StressCase).
void addMethodCases(std::vector<Case>& c, const MethodInfo& method) {
    const std::string name = method.name;
    for (float k : {1e-6f, 1e6f}) {
        std::string ks = k < 1.0f ? "1e-6" : "1e6";
        c.push_back({"light-" + ks + "-" + name, name, "Cornell box, light x" + ks, [name, k](StabilityResult& r) {
                         Measured m = rasterize(brighter(cornell(24), k), name, {}, 4);
                         Measured base = rasterize(cornell(24), name, {}, 4);
                         finish(r, m, ratioOf(m.mean, double(k) * base.mean), "linearity", 1e-2);
                     }});
    }
    for (float k : {1e-4f, 1e4f}) {
        std::string ks = k < 1.0f ? "1e-4" : "1e4";
        c.push_back({"scale-" + ks + "-" + name, name, "Cornell box scaled to " + ks + " m", [name, k](StabilityResult& r) {
                         Measured m = rasterize(placed(cornell(24), k), name, {}, 4);
                         Measured base = rasterize(cornell(24), name, {}, 4);
                         finish(r, m, ratioOf(m.mean, base.mean), "unscaled mean", 0.05);
                     }});
    }
    c.push_back({"bad-geometry-" + name, name, "Cornell box + bad triangles through the rasterizer and the method",
                 [name](StabilityResult& r) {
                     Measured m = rasterize(withBadGeometry(cornell(24)), name, {}, 4);
                     Measured base = rasterize(cornell(24), name, {}, 4);
                     finish(r, m, ratioOf(m.mean, base.mean), "clean scene", 1e-2);
                 }});
    c.push_back({"grazing-light-" + name, name, "sun 0.057 deg above the floor through the open front",
                 [name](StabilityResult& r) { finish(r, rasterize(grazing(cornell(24)), name, {}, 2), kNoRatio, "", 0.0); }});
    for (const StressCase& stress : method.stressCases)
        c.push_back({stress.name + "-" + name, name, stress.description, [name, stress](StabilityResult& r) {
                         const Scene s = stress.scene == StressCase::SceneKind::ClosedBox
                                             ? closedBox(stress.albedo, 0.0f, stress.size)
                                             : cornell(stress.size);
                         Measured m = rasterize(s, name, stress.settings(s), stress.frames);
                         if (!stress.against) {
                             finish(r, m, kNoRatio, "", 0.0);
                             return;
                         }
                         const SettingList against = stress.against(s);
                         Measured ref = rasterize(s, name, against, stress.frames);
                         finish(r, m, ratioOf(m.mean, ref.mean), "the run with " + settingsText(against), stress.tolerance);
                     }});
}

std::vector<Case> allCases() {
    std::vector<Case> c;
    for (float albedo : {0.99f, 0.999f}) {
        std::string a = albedo == 0.99f ? "0.99" : "0.999";
        c.push_back({"box-albedo-" + a + "-pathtrace", "pathtrace",
                     "closed box, every wall albedo " + a + " emitting 1 W/(m^2 sr): L = Le/(1-albedo)",
                     [albedo](StabilityResult& r) {
                         Measured m = pathTrace(closedBox(albedo, 1.0f, 8), 64);
                         finish(r, m, m.mean / (1.0 / (1.0 - double(albedo))), "Le/(1-albedo)",
                                albedo > 0.995f ? 0.15 : 0.05);
                     }});
    }
    for (float k : {1e-6f, 1e6f}) {
        std::string ks = k < 1.0f ? "1e-6" : "1e6";
        c.push_back({"light-" + ks + "-pathtrace", "pathtrace", "Cornell box, light x" + ks + ", same seed",
                     [k, ks](StabilityResult& r) {
                         Measured m = pathTrace(brighter(cornell(16), k), 16);
                         Measured base = pathTrace(cornell(16), 16);
                         finish(r, m, ratioOf(m.mean, double(k) * base.mean), "x" + ks + " the unscaled mean (linearity)", 1e-3);
                     }});
    }
    for (float k : {1e-4f, 1e4f}) {
        std::string ks = k < 1.0f ? "1e-4" : "1e4";
        c.push_back({"scale-" + ks + "-pathtrace", "pathtrace", "Cornell box scaled to " + ks + " m",
                     [k](StabilityResult& r) {
                         Measured m = pathTrace(placed(cornell(16), k), 32);
                         Measured base = pathTrace(cornell(16), 32);
                         finish(r, m, ratioOf(m.mean, base.mean), "unscaled mean (radiance is scale-free)", 0.02);
                     }});
    }
    // Far from the origin floats are coarser: ray offsets must follow the coordinates' magnitude
    // (1 m box at 1 km, 1 mm box at 1 m; the same seed, so only a bias moves the mean). At 1e-4 m
    // and 1 m the box's light would sit 0.7 units in the last place under its ceiling: not a scene
    // floats can hold.
    struct Placement {
        const char* name;
        float scale, offset;
        const char* description;
    };
    for (Placement p : {Placement{"moved-1km", 1.0f, 1000.0f, "Cornell box moved to (1000, 1000, 1000) m"},
                        Placement{"scale-1e-3-at-1m", 1e-3f, 1.0f, "Cornell box scaled to 1e-3 m, at (1, 1, 1) m"}}) {
        c.push_back({std::string(p.name) + "-pathtrace", "pathtrace", p.description, [p](StabilityResult& r) {
                         Measured m = pathTrace(placed(cornell(16), p.scale, p.offset), 32);
                         Measured base = pathTrace(cornell(16), 32);
                         finish(r, m, ratioOf(m.mean, base.mean), "the mean at the origin", 0.02);
                     }});
    }
    c.push_back({"bad-geometry-pathtrace", "pathtrace", "Cornell box + repeated-vertex, zero-area and NaN triangles",
                 [](StabilityResult& r) {
                     Measured m = pathTrace(withBadGeometry(cornell(16)), 16);
                     Measured base = pathTrace(cornell(16), 16);
                     finish(r, m, ratioOf(m.mean, base.mean), "clean scene", 1e-3);
                 }});
    c.push_back({"bad-geometry-voxelizer", "voxelizer",
                 "the same triangles voxelized (2 cm): active voxels vs the clean scene; largest = triangles skipped",
                 [](StabilityResult& r) {
                     VoxelizeSettings vs;
                     vs.voxelSize = 0.02f;
                     SparseGeometryVolume dirty = voxelizeScene(withBadGeometry(cornell(16)), vs);
                     SparseGeometryVolume clean = voxelizeScene(cornell(16), vs);
                     Measured m;
                     const VoxelizeStats& st = dirty.stats();
                     m.largest = double(st.skippedNonFinite + st.skippedDegenerate);
                     m.finite = st.skippedNonFinite >= 1 && st.skippedDegenerate >= 2;
                     finish(r, m, ratioOf(double(dirty.activeVoxelCount()), double(clean.activeVoxelCount())),
                            "clean scene's voxel count", 0.0);
                 }});
    c.push_back({"grazing-light-pathtrace", "pathtrace", "sun 0.057 deg above the floor through the open front",
                 [](StabilityResult& r) { finish(r, pathTrace(grazing(cornell(16)), 16), kNoRatio, "", 0.0); }});
    for (const MethodInfo& m : methods())
        if (m.built) addMethodCases(c, m);
    return c;
}

std::string fmt(double v) {
    if (std::isnan(v)) return "-";
    char buf[48];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

}  // namespace

std::vector<std::string> stabilityCaseNames() {
    std::vector<std::string> names;
    for (const Case& c : allCases()) names.push_back(c.name);
    return names;
}

std::vector<StabilityResult> runStabilityCases(const std::vector<std::string>& wanted) {
    std::vector<Case> cases = allCases();
    for (const std::string& w : wanted) {
        bool known = false;
        for (const Case& c : cases) known = known || c.name == w;
        if (!known) throw InputError("--cases " + w + ": unknown case");
    }
    std::vector<StabilityResult> results;
    for (const Case& c : cases) {
        if (!wanted.empty() && std::find(wanted.begin(), wanted.end(), c.name) == wanted.end()) continue;
        StabilityResult r;
        r.name = c.name;
        r.method = c.method;
        r.description = c.description;
        r.ratio = kNoRatio;
        std::printf("stability: %s...\n", c.name.c_str());
        std::fflush(stdout);
        auto start = std::chrono::steady_clock::now();
        try {
            c.run(r);
            r.ran = true;
        } catch (const NotImplementedError& e) {
            r.notRunReason = e.what();
        } catch (const std::exception& e) {
            // An exception on extreme input is a finding, not a crash of the suite.
            r.ran = true;
            r.finite = false;
            r.passed = false;
            r.notRunReason = std::string("threw: ") + e.what();
        }
        r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::printf("  %s\n", !r.ran ? ("not run: " + r.notRunReason).c_str() : r.passed ? "pass" : "FAIL");
        results.push_back(r);
    }
    return results;
}

bool runStabilitySuite(const std::string& dir, const std::vector<std::string>& wanted) {
    std::vector<StabilityResult> results = runStabilityCases(wanted);
    std::ostringstream md;
    md << "# voxgi stability suite\n\nCommand: `voxgi eval --stability -o " << dir << "`\n\n";
    md << "| case | method | finite | energy ratio | against | largest value | result | s | what |\n"
          "|---|---|---|---:|---|---:|---|---:|---|\n";
    nlohmann::json j = nlohmann::json::array();
    bool ok = true;
    for (const StabilityResult& r : results) {
        std::string verdict = !r.ran ? "not run: " + r.notRunReason : r.passed ? "pass" : "FAIL";
        if (r.ran && !r.passed && !r.notRunReason.empty()) verdict = "FAIL (" + r.notRunReason + ")";
        ok = ok && (!r.ran || r.passed);
        md << "| " << r.name << " | " << r.method << " | " << (r.ran ? (r.finite ? "yes" : "no") : "-") << " | "
           << fmt(r.ratio) << " | " << (r.expected.empty() ? "-" : r.expected) << " | "
           << (r.ran ? fmt(r.largest) : "-") << " | " << verdict << " | " << fmt(r.seconds) << " | " << r.description
           << " |\n";
        nlohmann::json jr{{"name", r.name},     {"method", r.method}, {"description", r.description},
                          {"ran", r.ran},       {"finite", r.finite}, {"largest", r.largest},
                          {"passed", r.passed}, {"seconds", r.seconds}, {"result", verdict}};
        jr["energy_ratio"] = std::isnan(r.ratio) ? nlohmann::json(nullptr) : nlohmann::json(r.ratio);
        jr["against"] = r.expected;
        j.push_back(jr);
    }
    writeTextAtomically(dir + "/stability.json", nlohmann::json{{"cases", j}}.dump(2) + "\n");
    writeTextAtomically(dir + "/stability.md", md.str());
    std::printf("wrote %s/stability.md and stability.json: %s\n", dir.c_str(), ok ? "all run cases pass" : "FAILURES");
    return ok;
}

}  // namespace voxgi::cli
