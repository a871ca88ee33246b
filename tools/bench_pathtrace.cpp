// voxgi bench pathtrace: rays per second of the reference path tracer on the Cornell box and
// Sponza (when the shared scenes are present), what Embree alone achieves on the same scene
// (where the time goes), and error against time (RMSE against a long render) as CSV.
#include <sys/resource.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "gi/metrics/image_metrics.h"
#include "gi/pathtrace/path_tracer.h"
#include "gi/raytrace/ray_tracer.h"
#include "scenes/atomic_file.h"
#include "scenes/errors.h"
#include "scenes/scene_loader.h"
#include "tools/bench_registry.h"
#include "tools/scene_arg.h"

namespace voxgi::cli {

namespace {

const char* kUsage =
    "voxgi bench pathtrace [--size 512] [--long-spp 256] [--max-spp 64] [--sponza-long-spp 32]\n"
    "       [--sponza-max-spp 8] [--sponza OBJ] [--csv curve.csv]\n"
    "  RMSE of the beauty layer against a long render (another seed) at 1, 2, 4... spp";

using Clock = std::chrono::steady_clock;

double seconds(Clock::time_point since) { return std::chrono::duration<double>(Clock::now() - since).count(); }

double cpuSeconds() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return double(u.ru_utime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec) + double(u.ru_stime.tv_sec) +
           1e-6 * double(u.ru_stime.tv_usec);
}

std::string defaultSponza() {
    const char* env = std::getenv("VOXGI_SCENES");
    std::string root = env ? env : "/work/shared/scenes";
    return root + "/crytek-sponza/sponza.obj";
}

Scene sponzaScene(const std::string& obj) {
    // Scale 0.01 (centimetres to metres), a sun through the open roof and a dim sky.
    std::string json = R"({
      "camera": {"eye": [-10.0, 2.0, -0.4], "target": [10.0, 4.0, 0.0], "fov": 60, "resolution": [512, 512]},
      "lights": [{"type": "directional", "direction": [0.25, -1.0, 0.15], "irradiance": 20}],
      "sky": {"radiance": [0.3, 0.4, 0.5]},
      "meshes": [{"type": "file", "path": ")" + obj + R"(", "transform": {"scale": 0.01}}]})";
    return parseSceneJson(json, obj);
}

// Embree alone on the scene's own rays: the camera's (coherent) and random ones from inside
// the bounds (incoherent, like bounces), single-ray queries over all threads.
void embreeAlone(const Scene& scene, int size) {
    RayTracer tracer(scene);
    Bounds b = scene.bounds();
    const int n = size * size;
    std::vector<glm::vec3> origins(static_cast<std::size_t>(n)), directions(static_cast<std::size_t>(n));
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (auto& o : origins) o = b.min + glm::vec3(u(rng), u(rng), u(rng)) * b.extent();
    for (auto& d : directions) {
        float z = 1.0f - 2.0f * u(rng), phi = 6.2831853f * u(rng), r = std::sqrt(std::max(0.0f, 1.0f - z * z));
        d = {r * std::cos(phi), r * std::sin(phi), z};
    }
    auto run = [&](const char* what, auto&& query) {
        auto start = Clock::now();
        double cpu = cpuSeconds();
        std::atomic<std::size_t> hits{0};
        tbb::parallel_for(tbb::blocked_range<int>(0, n, 1024), [&](const tbb::blocked_range<int>& r) {
            std::size_t local = 0;
            for (int i = r.begin(); i != r.end(); ++i) local += query(i) ? 1 : 0;
            hits += local;
        });
        double t = seconds(start), c = cpuSeconds() - cpu;
        std::printf("    embree alone, %-24s %7.2f M rays/s (%.2f M per CPU second)\n", what, n / t * 1e-6, n / c * 1e-6);
    };
    const Camera& cam = scene.camera;
    glm::vec3 fwd = glm::normalize(cam.target - cam.eye), right = glm::normalize(glm::cross(fwd, cam.up)),
              up = glm::cross(right, fwd);
    float th = std::tan(glm::radians(cam.fovYDegrees) * 0.5f);
    run("camera rays (intersect):", [&](int i) {
        float x = (float(i % size) + 0.5f) / float(size) * 2.0f - 1.0f, y = 1.0f - (float(i / size) + 0.5f) / float(size) * 2.0f;
        return tracer.intersect(cam.eye, glm::normalize(fwd + x * th * right + y * th * up)).hit;
    });
    run("random rays (intersect):", [&](int i) { return tracer.intersect(origins[std::size_t(i)], directions[std::size_t(i)]).hit; });
    run("random rays (occluded):", [&](int i) {
        return tracer.occluded(origins[std::size_t(i)], directions[std::size_t(i)], 0.0f, 1e30f);
    });
}

struct CurvePoint {
    int spp;
    double seconds, rays, rmse, relMse;
};

void benchScene(const std::string& name, Scene scene, int size, int longSpp, int maxSpp, std::ostringstream& csv) {
    scene.camera.width = scene.camera.height = size;
    std::printf("%s: %zu triangles, %dx%d\n", name.c_str(), scene.triangleCount(), size, size);
    embreeAlone(scene, size);

    PathTracerOptions o;
    o.seed = 1000;
    auto start = Clock::now();
    PathTracer reference(scene, o);
    double build = seconds(start);
    start = Clock::now();
    double cpu = cpuSeconds();
    reference.render(longSpp);
    double t = seconds(start), c = cpuSeconds() - cpu;
    double rays = double(reference.raysTraced());
    std::printf("    path tracer, long render %d spp: %.1f s, %.3g rays (%.2f per sample), %.2f M rays/s "
                "(%.2f M per CPU second), BVH %.2f s, dropped %llu\n",
                longSpp, t, rays, rays / (double(longSpp) * size * size), rays / t * 1e-6, rays / c * 1e-6, build,
                static_cast<unsigned long long>(reference.droppedSamples()));
    const Image ref = reference.image();

    o.seed = 1;
    PathTracer tracer(scene, o);
    double elapsed = 0.0;
    for (int spp = 1; spp <= maxSpp; spp *= 2) {
        auto s = Clock::now();
        tracer.render(spp - tracer.samplesPerPixel());
        elapsed += seconds(s);
        ImageMetrics m = computeMetrics(tracer.image(), ref, "beauty");
        std::printf("    %4d spp  %7.2f s  RMSE %.5f  relMSE %.5f  HDR-FLIP %.4f\n", spp, elapsed, m.rmse, m.relMse, m.flip);
        csv << name << "," << size << "," << spp << "," << elapsed << "," << tracer.raysTraced() << ","
            << double(tracer.raysTraced()) / elapsed * 1e-6 << "," << m.rmse << "," << m.relMse << "," << m.flip << ","
            << longSpp << "\n";
    }
}

int runBench(const std::vector<std::string>& argv) {
    Args args(argv, {"--size", "--long-spp", "--max-spp", "--sponza-long-spp", "--sponza-max-spp", "--sponza", "--csv"}, {});
    const int size = args.integer("--size", 512, 8, 8192);
    const int longSpp = args.integer("--long-spp", 256, 1, 1 << 20);
    const int maxSpp = args.integer("--max-spp", 64, 1, 1 << 20);
    const int sponzaLong = args.integer("--sponza-long-spp", 32, 1, 1 << 20);
    const int sponzaMax = args.integer("--sponza-max-spp", 8, 1, 1 << 20);
    const std::string sponza = args.value("--sponza", defaultSponza());
    if (auto c = args.value("--csv")) requireWritable(*c, "--csv");

    std::ostringstream csv;
    csv << "scene,size,spp,seconds,rays,mrays_per_s,rmse,relmse,flip,reference_spp\n";
    benchScene("cornell-box", loadSceneArgument("cornell-box"), size, longSpp, maxSpp, csv);
    if (std::filesystem::exists(sponza)) {
        auto start = Clock::now();
        Scene s = sponzaScene(sponza);
        std::printf("(Sponza loaded in %.1f s)\n", seconds(start));
        benchScene("sponza", std::move(s), size, sponzaLong, sponzaMax, csv);
    } else {
        std::printf("sponza: %s not found, skipped\n", sponza.c_str());
    }
    if (auto c = args.value("--csv")) {
        writeTextAtomically(*c, csv.str());
        std::printf("wrote %s\n", c->c_str());
    } else {
        std::printf("\n%s", csv.str().c_str());
    }
    return kOk;
}

}  // namespace

VOXGI_REGISTER_BENCHMARK("pathtrace", kUsage, runBench);

}  // namespace voxgi::cli
