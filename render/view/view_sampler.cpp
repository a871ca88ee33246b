#include "render/view/view_sampler.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <deque>
#include <limits>
#include <sstream>

#include "gi/raytrace/ray_tracer.h"
#include "gi/sampling/hash.h"
#include "render/view/view_script.h"
#include "scenes/atomic_file.h"
#include "scenes/errors.h"
#include "volumes/geometry_volume.h"

namespace voxgi::view {

namespace {

// A counter-based stream of uniform numbers in [0, 1): the n-th number of `key` is a hash.
class Uniforms {
public:
    explicit Uniforms(std::uint64_t key) : key_(mix64(key ^ 0x5EEDull)) {}
    float next() { return float(mix64(key_ + 0x9E3779B97F4A7C15ull * ++n_) >> 40) * (1.0f / 16777216.0f); }
    glm::vec3 direction() {
        const float z = 1.0f - 2.0f * next(), phi = 6.28318530718f * next();
        const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
        return {r * std::cos(phi), r * std::sin(phi), z};
    }

private:
    std::uint64_t key_;
    std::uint64_t n_ = 0;
};

// Probe rays in a fixed Fibonacci spiral: the same directions for every eye.
std::vector<glm::vec3> probeDirections(int n) {
    std::vector<glm::vec3> d;
    for (int i = 0; i < n; ++i) {
        const float z = 1.0f - (2.0f * float(i) + 1.0f) / float(n), phi = 2.39996322973f * float(i);
        const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
        d.push_back({r * std::cos(phi), r * std::sin(phi), z});
    }
    return d;
}

bool clearAround(const SparseGeometryVolume& occupancy, glm::ivec3 ijk) {
    for (int z = -1; z <= 1; ++z)
        for (int y = -1; y <= 1; ++y)
            for (int x = -1; x <= 1; ++x)
                if (occupancy.occupied(ijk + glm::ivec3(x, y, z))) return false;
    return true;
}

// The free space the scene's own camera stands in: the voxels of the occupancy's box, grown by
// two voxels so that the outside joins up around the scene, reached from the camera's eye
// through empty face neighbours. Eyes anywhere else stand in sealed cavities (Sponza's hollow
// walls and roof): no light arrives there, the reference is black and every method ties.
class ReachableSpace {
public:
    ReachableSpace(const SparseGeometryVolume& occupancy, glm::vec3 eye) {
        IndexBox box = occupancy.indexBounds();
        if (box.empty()) box = IndexBox{occupancy.voxelAt(eye), occupancy.voxelAt(eye)};
        min_ = box.min - 2;
        size_ = box.max - box.min + 5;
        reached_.assign(std::size_t(size_.x) * std::size_t(size_.y) * std::size_t(size_.z), 0);
        std::deque<glm::ivec3> front{start(occupancy, eye)};
        reached_[index(front.front())] = 1;
        const glm::ivec3 steps[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
        while (!front.empty()) {
            const glm::ivec3 v = front.front();
            front.pop_front();
            for (const glm::ivec3& step : steps) {
                const glm::ivec3 n = v + step;
                if (!inside(n) || reached_[index(n)] || occupancy.occupied(n)) continue;
                reached_[index(n)] = 1;
                front.push_back(n);
            }
        }
    }
    bool contains(glm::ivec3 ijk) const { return inside(ijk) && reached_[index(ijk)] != 0; }

private:
    bool inside(glm::ivec3 v) const {
        const glm::ivec3 l = v - min_;
        return l.x >= 0 && l.y >= 0 && l.z >= 0 && l.x < size_.x && l.y < size_.y && l.z < size_.z;
    }
    std::size_t index(glm::ivec3 v) const {
        const glm::ivec3 l = v - min_;
        return (std::size_t(l.z) * std::size_t(size_.y) + std::size_t(l.y)) * std::size_t(size_.x) + std::size_t(l.x);
    }
    // The eye's voxel (an eye outside the box starts from the box's empty rim), or when a
    // surface passes through it, the nearest empty voxel.
    glm::ivec3 start(const SparseGeometryVolume& occupancy, glm::vec3 eye) const {
        const glm::ivec3 v = glm::clamp(occupancy.voxelAt(eye), min_, min_ + size_ - 1);
        if (!occupancy.occupied(v)) return v;
        glm::ivec3 best = min_;
        long long bestDistance = std::numeric_limits<long long>::max();
        for (int z = 0; z < size_.z; ++z)
            for (int y = 0; y < size_.y; ++y)
                for (int x = 0; x < size_.x; ++x) {
                    const glm::ivec3 c = min_ + glm::ivec3(x, y, z), d = c - v;
                    const long long distance = 1LL * d.x * d.x + 1LL * d.y * d.y + 1LL * d.z * d.z;
                    if (distance < bestDistance && !occupancy.occupied(c)) {
                        bestDistance = distance;
                        best = c;
                    }
                }
        return best;
    }

    glm::ivec3 min_{0}, size_{0};
    std::vector<std::uint8_t> reached_;
};

}  // namespace

std::vector<Camera> sampleViews(const Scene& scene, const ViewSampling& sampling) {
    std::vector<Camera> views;
    if (sampling.count <= 0) return views;
    const Bounds bounds = scene.bounds();
    if (!bounds.valid()) throw InputError("--views: the scene has no geometry to place views in");
    const glm::vec3 extent = bounds.extent();
    const float longest = std::max(extent.x, std::max(extent.y, extent.z));
    if (!(longest > 0.0f)) throw InputError("--views: the scene's geometry is flat or a point");
    VoxelizeSettings settings;
    settings.voxelSize = longest / float(std::max(sampling.voxelsAcross, 4));
    const SparseGeometryVolume occupancy = voxelizeScene(scene, settings);
    const ReachableSpace reachable(occupancy, scene.camera.eye);
    const RayTracer tracer(scene);
    const std::vector<glm::vec3> probes = probeDirections(64);
    const glm::vec3 up = glm::normalize(scene.camera.up);
    const float diagonal = glm::length(extent);

    Uniforms u(sampling.seed);
    const long long maxCandidates = 400LL * sampling.count;
    for (long long candidate = 0; candidate < maxCandidates && int(views.size()) < sampling.count; ++candidate) {
        // An eye in the scene's box, at least a voxel from every surface, in the space the
        // scene's camera can reach.
        const glm::vec3 eye = bounds.min + glm::vec3(u.next(), u.next(), u.next()) * extent;
        const glm::ivec3 voxel = occupancy.voxelAt(eye);
        if (!reachable.contains(voxel) || !clearAround(occupancy, voxel)) continue;
        int hits = 0, backFaces = 0;
        for (const glm::vec3& d : probes) {
            const RayHit h = tracer.intersect(eye, d);
            if (!h.hit) continue;
            ++hits;
            backFaces += h.frontFace ? 0 : 1;
        }
        if (float(hits) < sampling.minSeenFraction * float(probes.size()) ||
            float(backFaces) > sampling.maxBackFaceFraction * float(hits))
            continue;
        // A target: of the front faces that 16 random directions meet some way off (not straight
        // above or below: the camera keeps the scene's up), the farthest, so the view looks
        // into the scene rather than at the nearest wall (a single plane, where every method
        // that bounces light between surfaces on screen has nothing to do).
        bool found = false;
        glm::vec3 target(0.0f);
        float farthest = std::max(2.0f * settings.voxelSize, sampling.minTargetDistance * longest);
        for (int attempt = 0; attempt < 16; ++attempt) {
            const glm::vec3 d = u.direction();
            if (std::abs(glm::dot(d, up)) > 0.9f) continue;
            const RayHit h = tracer.intersect(eye, d);
            if (!h.hit || !h.frontFace || h.t < farthest) continue;
            farthest = h.t;
            target = h.position;
            found = true;
        }
        if (!found) continue;
        Camera c = scene.camera;
        c.eye = eye;
        c.target = target;
        c.farPlane = std::max(c.farPlane, diagonal);
        views.push_back(c);
    }
    if (int(views.size()) < sampling.count)
        throw InputError("--views " + std::to_string(sampling.count) + ": found only " + std::to_string(views.size()) +
                         " views in the scene's free space after " + std::to_string(maxCandidates) + " candidate eyes");
    return views;
}

std::vector<Camera> readViews(const std::string& path, const Scene& scene) {
    const ViewScript script = ViewScript::load(path);
    if (script.keys().empty()) throw InputError(path + ": no camera keys (each key is one view)");
    std::vector<Camera> views;
    for (const CameraKey& k : script.keys()) {
        Camera c = scene.camera;
        c.eye = k.eye;
        c.target = k.target;
        views.push_back(c);
    }
    return views;
}

void writeViews(const std::string& path, const std::vector<Camera>& views) {
    std::ostringstream out;
    out.precision(9);
    out << "{\"keys\": [\n";
    for (std::size_t i = 0; i < views.size(); ++i) {
        const Camera& c = views[i];
        out << "  {\"frame\": " << i << ", \"eye\": [" << c.eye.x << ", " << c.eye.y << ", " << c.eye.z
            << "], \"target\": [" << c.target.x << ", " << c.target.y << ", " << c.target.z << "]}"
            << (i + 1 < views.size() ? ",\n" : "\n");
    }
    out << "]}\n";
    writeTextAtomically(path, out.str());
}

}  // namespace voxgi::view
