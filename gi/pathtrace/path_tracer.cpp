#include "gi/pathtrace/path_tracer.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <map>
#include <mutex>
#include <optional>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "gi/pathtrace/integrator.h"
#include "scenes/camera_rays.h"
#include "scenes/errors.h"
#include "scenes/memory_limit.h"

namespace voxgi {

namespace {

constexpr int kTile = 16;
// Light subpaths per sample index: one per kPixelsPerLightPath pixels, at least kMinLightPaths
// and at most kMaxLightPaths. Camera vertices pick their connections from the whole pool, which
// need only sample where the light lands: at 128^2, 16 times fewer subpaths than pixels (256 to
// 16384 of them) left the noise per sample unchanged in Sibenik and the Cornell box, and one per
// pixel cost the Cornell box 60 % more time (docs/reference.md). Sharing a pool among more
// pixels costs correlation between them within a sample index, not bias.
constexpr int kPixelsPerLightPath = 16;
constexpr int kMinLightPaths = 256;
constexpr int kMaxLightPaths = 1 << 16;
// Paths a thread traces at once (Integrator::traceBatch): enough that one path's cache misses
// load while the others work.
constexpr int kPathsInFlight = 16;
// Sample indices rendered together: their light vertices are held at once.
constexpr int kSamplesPerPass = 8;
// Light vertices kept for samplePixel() callers.
constexpr std::size_t kKeptPools = 16;
// Light subpath j of sample s draws from the sampler of "pixel" kLightStream + j.
constexpr std::uint64_t kLightStream = 0xFFFF000000000000ull;

// Whether every quad light already has its emitting mesh (Scene::addQuadLightGeometry).
bool hasQuadGeometry(const Scene& scene) {
    for (std::size_t i = 0; i < scene.lights.size(); ++i)
        if (scene.lights[i].type == LightType::Quad && !scene.quadLightMesh(i)) return false;
    return true;
}

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

struct PixelSum {
    glm::dvec3 direct{0.0}, indirect{0.0};
    glm::dvec3 albedo{0.0}, normal{0.0};
    double depth = 0.0;
    std::uint32_t count = 0;
};

}  // namespace

struct PathTracer::Impl {
    std::optional<Scene> owned;
    const Scene& scene;
    PathTracerOptions options;
    int width, height;
    RayTracer tracer;
    pt::Integrator integrator;
    // A pinhole with glm::lookAt / glm::perspective's conventions.
    CameraRays camera;
    std::vector<PixelSum> sums;
    int samples = 0;
    std::atomic<std::uint64_t> rays{0}, dropped{0};
    int lightPaths = 0;  // per sample index; 0: unidirectional
    std::mutex keptMutex;
    std::map<std::uint64_t, std::shared_ptr<const pt::LightVertices>> kept;

    static const Scene& pick(const Scene& given, std::optional<Scene>& owned) {
        if (hasQuadGeometry(given)) return given;
        owned.emplace(given);
        owned->addQuadLightGeometry();
        return *owned;
    }

    Impl(const Scene& s, const PathTracerOptions& o)
        : scene(pick(s, owned)), options(o), width(o.width > 0 ? o.width : s.camera.width),
          height(o.height > 0 ? o.height : s.camera.height), tracer(scene),
          integrator(scene, tracer, o.maxBounces, o.caustics), camera(scene.camera, std::max(width, 1), std::max(height, 1)) {
        if (width <= 0 || height <= 0) throw InputError("path tracer: image size must be positive");
        // Refuse before allocating: an absurd size would otherwise end in the OOM killer.
        requireMemory(double(width) * double(height) * double(sizeof(PixelSum) + 16 * sizeof(float)),
                      "path tracer: " + std::to_string(width) + "x" + std::to_string(height) + " accumulation and image buffers");
        sums.resize(std::size_t(width) * std::size_t(height));
        if (options.lightPaths && options.caustics && integrator.tracesLightPaths()) {
            lightPaths = int(std::clamp<std::int64_t>(std::int64_t(width) * height / kPixelsPerLightPath, kMinLightPaths,
                                                      kMaxLightPaths));
            // At most maxLightVertices() per subpath, for each
            // pass's samples and the pools kept for samplePixel().
            requireMemory(double(lightPaths) * double(kSamplesPerPass + kKeptPools) * integrator.maxLightVertices() *
                              sizeof(pt::LightVertex),
                          "path tracer: " + std::to_string(lightPaths) + " light subpaths per sample");
        }
    }

    // The light vertices of sample `index` (parallel over subpaths; deterministic: each block
    // of subpaths fills its own list, and the lists join in block order).
    std::shared_ptr<const pt::LightVertices> traceLightPaths(std::uint64_t index) const {
        constexpr int kBlock = 256;
        const int blocks = (lightPaths + kBlock - 1) / kBlock;
        std::vector<std::vector<pt::LightVertex>> lists(static_cast<std::size_t>(blocks));
        std::atomic<std::uint64_t> traced{0};
        // Isolated: samplePixel() callers trace these under a lock from inside their own
        // parallel loops, and a thread waiting here must not pick up one of those (it would
        // take the lock again).
        tbb::this_task_arena::isolate([&] {
            tbb::parallel_for(0, blocks, [&](int b) {
                std::uint64_t local = 0;
                std::vector<pt::LightVertex>& list = lists[std::size_t(b)];
                for (int j = b * kBlock; j < std::min(lightPaths, (b + 1) * kBlock); ++j)
                    local += integrator.traceLightPath(
                        pt::PathSampler(options.seed, kLightStream + std::uint64_t(j), index), list);
                traced += local;
            });
        });
        auto pool = std::make_shared<pt::LightVertices>();
        std::size_t total = 0;
        for (const auto& list : lists) total += list.size();
        pool->vertices.reserve(total);
        for (const auto& list : lists) pool->vertices.insert(pool->vertices.end(), list.begin(), list.end());
        pool->paths = std::uint32_t(lightPaths);
        pool->rays = traced.load();
        return pool;
    }

    // For samplePixel(): the light vertices of `index`, traced on first use and kept for a while.
    std::shared_ptr<const pt::LightVertices> keptLightPaths(std::uint64_t index) {
        if (lightPaths == 0) return nullptr;
        std::lock_guard<std::mutex> lock(keptMutex);
        auto found = kept.find(index);
        if (found != kept.end()) return found->second;
        if (kept.size() >= kKeptPools) kept.erase(kept.begin());
        return kept[index] = traceLightPaths(index);
    }

    pt::PathSampler pixelSampler(int x, int y, std::uint64_t index) const {
        return pt::PathSampler(options.seed, std::uint64_t(y) * std::uint64_t(width) + std::uint64_t(x), index);
    }
    // The camera ray through pixel (x, y) for `sampler`'s decision 0. Box filter: a uniform point
    // in the pixel, as the rasterizer's jittered accumulation.
    glm::vec3 cameraDirection(int x, int y, const pt::PathSampler& sampler) const {
        const glm::vec2 jitter = sampler.get2D(0);
        return glm::normalize(camera.direction((float(x) + jitter.x) / float(width), (float(y) + jitter.y) / float(height)));
    }

    PathSample samplePixel(int x, int y, std::uint64_t index, const pt::LightVertices* lightVertices) const {
        const pt::PathSampler sampler = pixelSampler(x, y, index);
        return integrator.trace(camera.eye, cameraDirection(x, y, sampler), sampler, lightVertices);
    }

    // Samples first .. first + count - 1 of every pixel of `tile`; pools[s] holds sample
    // first + s's light vertices (null: unidirectional).
    void renderTile(int tile, int first, int count, const std::vector<std::shared_ptr<const pt::LightVertices>>& pools) {
        int tilesX = (width + kTile - 1) / kTile;
        int x0 = (tile % tilesX) * kTile, y0 = (tile / tilesX) * kTile;
        int x1 = std::min(x0 + kTile, width), y1 = std::min(y0 + kTile, height);
        std::uint64_t tileRays = 0, tileDropped = 0;
        const int pixels = (x1 - x0) * (y1 - y0);
        std::vector<glm::vec3> origins(static_cast<std::size_t>(pixels), camera.eye), directions(origins.size());
        std::vector<RayHit> firstHits(origins.size());
        std::vector<pt::Integrator::PathStart> starts;
        starts.reserve(origins.size());
        std::vector<PathSample> samples(origins.size());
        // Sample by sample over the tile: one pool of light vertices (megabytes) is in use at a
        // time, not all of the pass's. Each pixel still sums its samples in order.
        for (int s = 0; s < count; ++s) {
            const std::uint64_t index = std::uint64_t(first + s);
            // The tile's camera rays first, through Embree together: neighbouring pixels' rays
            // share their traversal in SIMD packets.
            starts.clear();
            for (int y = y0, i = 0; y < y1; ++y)
                for (int x = x0; x < x1; ++x, ++i) {
                    const pt::PathSampler sampler = pixelSampler(x, y, index);
                    directions[std::size_t(i)] = cameraDirection(x, y, sampler);
                    starts.push_back({camera.eye, directions[std::size_t(i)], sampler, &firstHits[std::size_t(i)]});
                }
            tracer.intersectCoherent(origins.data(), directions.data(), pixels, firstHits.data());
            for (int i = 0; i < pixels; i += kPathsInFlight)
                integrator.traceBatch(&starts[std::size_t(i)], std::min(kPathsInFlight, pixels - i), pools[std::size_t(s)].get(),
                                      &samples[std::size_t(i)]);
            for (int y = y0, i = 0; y < y1; ++y)
                for (int x = x0; x < x1; ++x, ++i) {
                    PixelSum& sum = sums[std::size_t(y) * std::size_t(width) + std::size_t(x)];
                    const PathSample& p = samples[std::size_t(i)];
                    tileRays += p.rays;
                    if (!finite(p.direct) || !finite(p.indirect) || !finite(p.albedo) || !finite(p.normal) ||
                        !std::isfinite(p.depth)) {
                        ++tileDropped;
                        continue;
                    }
                    sum.direct += glm::dvec3(p.direct);
                    sum.indirect += glm::dvec3(p.indirect);
                    sum.albedo += glm::dvec3(p.albedo);
                    sum.normal += glm::dvec3(p.normal);
                    sum.depth += double(p.depth);
                    ++sum.count;
                }
        }
        rays += tileRays;
        dropped += tileDropped;
    }
};

PathTracer::PathTracer(const Scene& scene, const PathTracerOptions& options)
    : impl_(std::make_unique<Impl>(scene, options)) {}
PathTracer::~PathTracer() = default;

void PathTracer::render(int samples) {
    if (samples <= 0) return;
    Impl& m = *impl_;
    int tiles = ((m.width + kTile - 1) / kTile) * ((m.height + kTile - 1) / kTile);
    for (int done = 0; done < samples;) {
        const int first = m.samples + done, count = std::min(kSamplesPerPass, samples - done);
        auto pools = std::vector<std::shared_ptr<const pt::LightVertices>>(std::size_t(count));
        if (m.lightPaths > 0)
            for (int s = 0; s < count; ++s) {
                pools[std::size_t(s)] = m.traceLightPaths(std::uint64_t(first + s));
                m.rays += pools[std::size_t(s)]->rays;
            }
        tbb::parallel_for(tbb::blocked_range<int>(0, tiles, 1), [&](const tbb::blocked_range<int>& r) {
            for (int t = r.begin(); t != r.end(); ++t) m.renderTile(t, first, count, pools);
        });
        done += count;
    }
    m.samples += samples;
}

Image PathTracer::image() const {
    const Impl& m = *impl_;
    Image img(m.width, m.height);
    // Create every layer first: later layer() calls would move the ones already referenced.
    for (const char* name : {"beauty", "direct", "indirect", "albedo", "normal"}) img.layer(name);
    img.layer("depth", 1);
    ImageLayer& beauty = img.layer("beauty");
    ImageLayer& direct = img.layer("direct");
    ImageLayer& indirect = img.layer("indirect");
    ImageLayer& albedo = img.layer("albedo");
    ImageLayer& normal = img.layer("normal");
    ImageLayer& depth = img.layer("depth", 1);
    for (std::size_t i = 0; i < m.sums.size(); ++i) {
        const PixelSum& s = m.sums[i];
        double inv = s.count > 0 ? 1.0 / double(s.count) : 0.0;
        for (int c = 0; c < 3; ++c) {
            std::size_t k = 3 * i + std::size_t(c);
            direct.data[k] = float(s.direct[c] * inv);
            indirect.data[k] = float(s.indirect[c] * inv);
            beauty.data[k] = float((s.direct[c] + s.indirect[c]) * inv);
            albedo.data[k] = float(s.albedo[c] * inv);
            normal.data[k] = float(s.normal[c] * inv);
        }
        depth.data[i] = float(s.depth * inv);
    }
    return img;
}

int PathTracer::width() const { return impl_->width; }
int PathTracer::height() const { return impl_->height; }
int PathTracer::samplesPerPixel() const { return impl_->samples; }
std::uint64_t PathTracer::raysTraced() const { return impl_->rays.load(); }
std::uint64_t PathTracer::droppedSamples() const { return impl_->dropped.load(); }

PathSample PathTracer::samplePixel(int x, int y, std::uint64_t index) const {
    return impl_->samplePixel(x, y, index, impl_->keptLightPaths(index).get());
}

const RayTracer& PathTracer::rayTracer() const { return impl_->tracer; }

PathSample PathTracer::trace(glm::vec3 origin, glm::vec3 direction, std::uint64_t stream) const {
    const pt::PathSampler sampler(impl_->options.seed, ~std::uint64_t(0), stream);
    return impl_->integrator.trace(origin, glm::normalize(direction), sampler);
}

}  // namespace voxgi
