// Triangles -> level-0 voxel sums. The index space is cut into 32^3-voxel bins (4^3 leaves);
// each triangle is listed in every bin its bounding box reaches and each bin is one TBB task
// that owns its leaves, so no two threads ever write the same voxel and no merge is needed.
// Inside a bin a triangle walks the columns along its dominant normal axis; each column holds
// at most a few candidate voxels, each confirmed by the separating-axis test and then clipped
// for its exact covered area.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <unordered_map>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "scenes/errors.h"
#include "scenes/memory_limit.h"
#include "shaders/shared/material.h"
#include "volumes/detail/accumulation.h"
#include "volumes/detail/voxelizer.h"
#include "volumes/triangle_box.h"

namespace voxgi::detail {

namespace {

constexpr int kBin = 32;               // voxels per bin side, a multiple of the leaf size
constexpr int kLeavesPerBin = kBin / 8;
constexpr float kSlack = 1e-4f;        // box growth (voxels) that keeps touching triangles in
constexpr float kTouchWeight = 1e-6f;  // albedo weight of a voxel a triangle only touches

struct SmallTexture;

// A triangle as the rasterizer uses it, made from its mesh when a bin needs it (TriangleSource):
// the list of all triangles holds only references, a tenth of the memory.
struct PreparedTriangle {
    glm::vec3 p[3];          // world space
    glm::vec3 unitNormal;
    glm::vec3 albedo;        // material diffuse albedo, times the texture average when sampled nowhere
    const SmallTexture* texture;  // sampled at each piece's centroid when the mesh has uvs
    glm::vec2 uv[3];
    glm::ivec3 lo, hi;       // voxels touched by the bounding box (closed boxes, with slack)
};

std::uint64_t binKey(const glm::ivec3& b) {
    return (std::uint64_t(std::uint32_t(b.x) & 0x1fffff) << 42) | (std::uint64_t(std::uint32_t(b.y) & 0x1fffff) << 21) |
           std::uint64_t(std::uint32_t(b.z) & 0x1fffff);
}

glm::ivec3 floorDiv(const glm::ivec3& v, int d) {
    return glm::ivec3(int(std::floor(double(v.x) / d)), int(std::floor(double(v.y) / d)), int(std::floor(double(v.z) / d)));
}

// A small linear-RGB copy of each diffuse texture (at most 64x64 cells, each the mean of a
// strided sample of its texels). A voxel piece spans many texels anyway, and a table that fits
// in cache keeps textured scenes as fast as untextured ones: point lookups into the full
// images were half the rasterizer's time on Sponza, all of it cache misses.
struct SmallTexture {
    int width = 0, height = 0;
    std::vector<glm::vec3> texels;  // rows top first, like Texture

    explicit SmallTexture(const Texture& t) {
        static const struct SrgbTable {
            float value[256];
            SrgbTable() {
                for (int i = 0; i < 256; ++i) {
                    float c = float(i) / 255.0f;
                    value[i] = c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
                }
            }
        } table;
        width = std::min(t.width, 64);
        height = std::min(t.height, 64);
        texels.resize(std::size_t(width) * std::size_t(height));
        for (int cy = 0; cy < height; ++cy)
            for (int cx = 0; cx < width; ++cx) {
                int x0 = cx * t.width / width, x1 = (cx + 1) * t.width / width;
                int y0 = cy * t.height / height, y1 = (cy + 1) * t.height / height;
                int sx = std::max(1, (x1 - x0) / 4), sy = std::max(1, (y1 - y0) / 4);
                glm::vec3 sum(0.0f);
                int n = 0;
                for (int y = y0; y < y1; y += sy)
                    for (int x = x0; x < x1; x += sx, ++n) {
                        const std::uint8_t* p = &t.rgba[(std::size_t(y) * std::size_t(t.width) + std::size_t(x)) * 4];
                        sum += glm::vec3(table.value[p[0]], table.value[p[1]], table.value[p[2]]);
                    }
                texels[std::size_t(cy) * std::size_t(width) + std::size_t(cx)] = sum / float(std::max(n, 1));
            }
    }

    glm::vec3 at(glm::vec2 uv) const {
        float u = uv.x - std::floor(uv.x), v = 1.0f - (uv.y - std::floor(uv.y));
        int x = std::min(width - 1, std::max(0, int(u * float(width))));
        int y = std::min(height - 1, std::max(0, int(v * float(height))));
        return texels[std::size_t(y) * std::size_t(width) + std::size_t(x)];
    }
};

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Voxels i whose closed box [i, i+1] (grown by kSlack) reaches x, over an interval [lo, hi].
int firstVoxel(double lo) { return int(std::ceil(lo - 1.0 - kSlack)); }
int lastVoxel(double hi) { return int(std::floor(hi + kSlack)); }

constexpr int kBinLeaves = kLeavesPerBin * kLeavesPerBin * kLeavesPerBin;

// A thread's dense sums, one per leaf of a bin, reused from bin to bin (packing zeroes them).
struct BinScratch {
    std::unique_ptr<DenseSums[]> leaves = std::make_unique<DenseSums[]>(kBinLeaves);
};

class BinRasterizer {
public:
    BinRasterizer(const glm::ivec3& bin, double voxelSize, BinScratch& scratch)
        : origin_(bin * kBin), h_(voxelSize), scratch_(scratch) {}

    void add(const PreparedTriangle& t, std::size_t& tests) {
        glm::vec3 q[3];
        for (int i = 0; i < 3; ++i)
            q[i] = glm::vec3(glm::dvec3(t.p[i]) / h_ - glm::dvec3(origin_));
        const glm::ivec3 lo = glm::max(t.lo - origin_, glm::ivec3(0));
        const glm::ivec3 hi = glm::min(t.hi - origin_, glm::ivec3(kBin - 1));
        if (lo.x > hi.x || lo.y > hi.y || lo.z > hi.z) return;
        const glm::vec3 n = t.unitNormal;
        const glm::vec3 an = glm::abs(n);
        const int d = an.x >= an.y && an.x >= an.z ? 0 : (an.y >= an.z ? 1 : 2);
        const int u = (d + 1) % 3, v = (d + 2) % 3;
        const float planeOffset = glm::dot(n, q[0]);
        const float dMin = std::min(q[0][d], std::min(q[1][d], q[2][d]));
        const float dMax = std::max(q[0][d], std::max(q[1][d], q[2][d]));
        // The triangle is clipped to each row of columns once, the row to each column once, and
        // the column to each voxel: two planes a voxel instead of six.
        ClipPolygon triangle;
        triangle.v[0] = q[0];
        triangle.v[1] = q[1];
        triangle.v[2] = q[2];
        triangle.count = 3;
        glm::ivec3 cell;
        for (int iu = lo[u]; iu <= hi[u]; ++iu) {
            ClipPolygon row = triangle;
            clipToSlab(row, u, float(iu), float(iu + 1));
            for (int iv = lo[v]; iv <= hi[v]; ++iv) {
                // The plane's extent along d over this column (|n_d| is the largest component,
                // so the column holds at most ~3 candidates), cut to the triangle's extent.
                float colLo = 1e30f, colHi = -1e30f;
                for (int corner = 0; corner < 4; ++corner) {
                    float pu = float(iu) + ((corner & 1) ? 1.0f + kSlack : -kSlack);
                    float pv = float(iv) + ((corner & 2) ? 1.0f + kSlack : -kSlack);
                    float pd = (planeOffset - n[u] * pu - n[v] * pv) / n[d];
                    colLo = std::min(colLo, pd);
                    colHi = std::max(colHi, pd);
                }
                int first = std::max(lo[d], firstVoxel(std::max(colLo, dMin)));
                int last = std::min(hi[d], lastVoxel(std::min(colHi, dMax)));
                if (first > last) continue;
                ClipPolygon column = row;
                clipToSlab(column, v, float(iv), float(iv + 1));
                cell[u] = iu;
                cell[v] = iv;
                for (int id = first; id <= last; ++id) {
                    cell[d] = id;
                    ++tests;
                    const glm::vec3 boxLo(cell);
                    // The clipped piece is needed anyway; a piece with area proves the overlap,
                    // so the separating-axis test runs only for the rest (touching or outside).
                    ClipPolygon piece = column;
                    clipToSlab(piece, d, float(id), float(id + 1));
                    const PolygonMoments m = polygonMoments(piece);
                    if (!(m.area > 0.0f) &&
                        !triangleOverlapsBox(q[0], q[1], q[2], boxLo + 0.5f, glm::vec3(0.5f), kSlack))
                        continue;
                    accumulate(t, q, cell, boxLo, piece, m);
                }
            }
        }
    }

    // Packs the touched leaves and moves them out, with origins in global index space.
    void collect(AccumLevel& out) {
        for (int i = 0; i < kBinLeaves; ++i)
            if (auto& leaf = leaves_[i]) {
                leaf->pack(scratch_.leaves[std::size_t(i)]);
                leaf->translate(origin_);
                out.push_back(std::move(leaf));
            }
    }

private:
    void accumulate(const PreparedTriangle& t, const glm::vec3 q[3], const glm::ivec3& cell, const glm::vec3& boxLo,
                    const ClipPolygon& piece, PolygonMoments m) {
        const glm::ivec3 l = cell >> 3;
        const int slot = (l.x * kLeavesPerBin + l.y) * kLeavesPerBin + l.z;
        auto& leaf = leaves_[slot];
        if (!leaf) leaf = std::make_unique<AccumLeaf>(l * 8);
        const int offset = AccumLeaf::offset(cell.x, cell.y, cell.z);

        const glm::vec3 boxHi = boxLo + 1.0f;
        // A piece lying flat on the box's upper face belongs to the neighbour above, whose
        // lower face it is: covered area is counted once, occupancy in both.
        for (int axis = 0; axis < 3 && m.area > 0.0f; ++axis) {
            bool flat = true;
            for (int i = 0; i < piece.count && flat; ++i) flat = piece.v[i][axis] == boxHi[axis];
            if (flat) m.area = 0.0f;
        }
        VoxelSums s;
        s.area = m.area;
        s.vectorArea = m.area * t.unitNormal;
        s.axisArea = m.area * glm::abs(t.unitNormal);
        glm::vec3 albedo = t.albedo;
        if (t.texture) albedo *= t.texture->at(uvAt(t, q, m.area > 0.0f ? m.centroid : piece.count ? piece.v[0] : q[0]));
        const float w = m.area + kTouchWeight;
        s.albedoSum = w * albedo;
        s.albedoWeight = w;
        leaf->add(offset, s, scratch_.leaves[std::size_t(slot)]);
    }

    static glm::vec2 uvAt(const PreparedTriangle& t, const glm::vec3 q[3], const glm::vec3& x) {
        glm::vec3 n = glm::cross(q[1] - q[0], q[2] - q[0]);
        float inv = 1.0f / glm::dot(n, n);
        float wa = glm::dot(glm::cross(q[1] - x, q[2] - x), n) * inv;
        float wb = glm::dot(glm::cross(q[2] - x, q[0] - x), n) * inv;
        return wa * t.uv[0] + wb * t.uv[1] + (1.0f - wa - wb) * t.uv[2];
    }

    glm::ivec3 origin_;
    double h_;
    BinScratch& scratch_;
    std::unique_ptr<AccumLeaf> leaves_[kBinLeaves];
};

// Where a triangle's data lives: its mesh and face. prepare() makes the rasterizer's record with
// the same arithmetic every time, so a triangle read twice gives the same voxels.
struct TriangleRef {
    std::uint32_t mesh, face;
};

struct TriangleSource {
    const Scene& scene;
    double h;
    const std::vector<char>& textureUsable;
    const std::vector<std::unique_ptr<SmallTexture>>& smallTextures;

    const Material* material(const Mesh& mesh, std::size_t f) const {
        return mesh.materialIds.size() > f && mesh.materialIds[f] < scene.materials.size()
                   ? &scene.materials[mesh.materialIds[f]] : nullptr;
    }

    // The face's material's albedo texture when it has pixels to read, else -1.
    int albedoTexture(const Mesh& mesh, std::size_t f) const {
        const Material* m = material(mesh, f);
        const int t = m ? m->albedoTexture : -1;
        return t >= 0 && std::size_t(t) < scene.textures.size() && textureUsable[std::size_t(t)] ? t : -1;
    }

    // Positions, normal and the voxels its bounding box touches.
    PreparedTriangle bounds(const TriangleRef& r) const {
        const Mesh& mesh = scene.meshes[r.mesh];
        PreparedTriangle t;
        for (int i = 0; i < 3; ++i) t.p[i] = mesh.positions[mesh.indices[3 * std::size_t(r.face) + std::size_t(i)]];
        glm::dvec3 e0 = glm::dvec3(t.p[1]) - glm::dvec3(t.p[0]), e1 = glm::dvec3(t.p[2]) - glm::dvec3(t.p[0]);
        glm::dvec3 cr = glm::cross(e0, e1);
        t.unitNormal = glm::vec3(cr / glm::length(cr));
        glm::dvec3 lo = glm::min(glm::dvec3(t.p[0]), glm::min(glm::dvec3(t.p[1]), glm::dvec3(t.p[2]))) / h;
        glm::dvec3 hi = glm::max(glm::dvec3(t.p[0]), glm::max(glm::dvec3(t.p[1]), glm::dvec3(t.p[2]))) / h;
        t.lo = glm::ivec3(firstVoxel(lo.x), firstVoxel(lo.y), firstVoxel(lo.z));
        t.hi = glm::ivec3(lastVoxel(hi.x), lastVoxel(hi.y), lastVoxel(hi.z));
        t.texture = nullptr;
        return t;
    }

    // bounds() plus the surface: diffuse albedo and texture.
    PreparedTriangle prepare(const TriangleRef& r) const {
        PreparedTriangle t = bounds(r);
        const Mesh& mesh = scene.meshes[r.mesh];
        const Material* material = this->material(mesh, r.face);
        // The diffuse albedo: what the voxel's surfaces bounce as Lambert light.
        t.albedo = material ? shading::diffuseAlbedo(material->albedo, material->metallic, material->specular, material->transmission)
                            : glm::vec3(0.8f);
        if (const int texture = albedoTexture(mesh, r.face); texture >= 0) {
            if (mesh.uvs.size() == mesh.positions.size()) {
                t.texture = smallTextures[std::size_t(texture)].get();
                for (int i = 0; i < 3; ++i) t.uv[i] = mesh.uvs[mesh.indices[3 * std::size_t(r.face) + std::size_t(i)]];
            } else {
                t.albedo *= scene.textures[std::size_t(texture)].averageLinear;
            }
        }
        return t;
    }
};

}  // namespace

AccumLevel voxelizeTriangles(const Scene& scene, const VoxelizeSettings& settings, VoxelizeStats& stats) {
    const double h = settings.voxelSize;
    // Index coordinates stay far inside int range, and bins inside their 21-bit key fields.
    const double maxIndex = double(kBin) * double(1 << 19);
    std::vector<char> textureUsable(scene.textures.size(), 0);
    for (std::size_t i = 0; i < scene.textures.size(); ++i) {
        const Texture& t = scene.textures[i];
        textureUsable[i] = t.width > 0 && t.height > 0 &&
                           t.rgba.size() >= std::size_t(t.width) * std::size_t(t.height) * 4;
    }
    std::vector<std::unique_ptr<SmallTexture>> smallTextures(scene.textures.size());
    const TriangleSource source{scene, h, textureUsable, smallTextures};
    std::vector<TriangleRef> triangles;
    triangles.reserve(scene.triangleCount());
    double estimate = 0.0;
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
        const Mesh& mesh = scene.meshes[m];
        for (std::size_t f = 0; f < mesh.triangleCount(); ++f) {
            ++stats.triangles;
            std::uint32_t idx[3] = {mesh.indices[3 * f], mesh.indices[3 * f + 1], mesh.indices[3 * f + 2]};
            if (idx[0] >= mesh.positions.size() || idx[1] >= mesh.positions.size() || idx[2] >= mesh.positions.size()) {
                ++stats.skippedDegenerate;
                continue;
            }
            glm::vec3 p[3];
            for (int i = 0; i < 3; ++i) p[i] = mesh.positions[idx[i]];
            if (!finite(p[0]) || !finite(p[1]) || !finite(p[2])) {
                ++stats.skippedNonFinite;
                continue;
            }
            glm::dvec3 e0 = glm::dvec3(p[1]) - glm::dvec3(p[0]), e1 = glm::dvec3(p[2]) - glm::dvec3(p[0]);
            double twiceArea = glm::length(glm::cross(e0, e1));
            double longest = std::max(glm::dot(e0, e0), std::max(glm::dot(e1, e1), glm::dot(e1 - e0, e1 - e0)));
            // Zero area, repeated vertices, or a sliver whose normal is rounding noise.
            if (!(twiceArea > 1e-7 * longest) || !std::isfinite(twiceArea)) {
                ++stats.skippedDegenerate;
                continue;
            }
            glm::dvec3 lo = glm::min(glm::dvec3(p[0]), glm::min(glm::dvec3(p[1]), glm::dvec3(p[2]))) / h;
            glm::dvec3 hi = glm::max(glm::dvec3(p[0]), glm::max(glm::dvec3(p[1]), glm::dvec3(p[2]))) / h;
            for (int k = 0; k < 3; ++k)
                if (std::abs(lo[k]) > maxIndex || std::abs(hi[k]) > maxIndex)
                    throw InputError("--voxel-size " + std::to_string(settings.voxelSize) +
                                     ": scene coordinates exceed the index range at this voxel size");
            const TriangleRef ref{std::uint32_t(m), std::uint32_t(f)};
            const PreparedTriangle t = source.bounds(ref);
            // Voxels a triangle can touch: its area crosses at most ~sqrt(3) voxel layers, its
            // edges add a rim; never more than its bounding box.
            glm::dvec3 ext = glm::dvec3(t.hi - t.lo) + 1.0;
            double perimeter = (glm::length(e0) + glm::length(e1) + glm::length(e1 - e0)) / h;
            estimate += std::min(ext.x * ext.y * ext.z, 1.8 * twiceArea / (h * h) + 2.0 * perimeter + 8.0);
            // Each texture's small copy is made here, before the threads read them.
            const int texture = source.albedoTexture(mesh, f);
            if (texture >= 0 && mesh.uvs.size() == mesh.positions.size() && !smallTextures[std::size_t(texture)])
                smallTextures[std::size_t(texture)] = std::make_unique<SmallTexture>(scene.textures[std::size_t(texture)]);
            triangles.push_back(ref);
        }
    }
    stats.trianglesUsed = triangles.size();
    stats.estimatedVoxels = std::uint64_t(std::min(estimate, 1.8e19));
    std::uint64_t levelsEstimate = stats.estimatedVoxels + stats.estimatedVoxels / 3;  // + coarser levels
    if (levelsEstimate > settings.maxVoxels)
        throw InputError("--voxel-size " + std::to_string(settings.voxelSize) + ": about " +
                         std::to_string(levelsEstimate) + " voxels estimated, above --max-voxels " +
                         std::to_string(settings.maxVoxels) + "; use a larger voxel size");
    // Held at the peak, while a level is finished: every level's packed sums, the finished
    // level's attributes (normal and c0, albedo and projected-coverage halves) and occupancy
    // leaves of ~1/6 fill.
    const double perVoxel =
        double(sizeof(VoxelSums) + sizeof(glm::vec4) + 2 * sizeof(detail::Half3)) + 64.0 / 6.0;
    requireMemory(double(levelsEstimate) * perVoxel, "voxelizing at --voxel-size " + std::to_string(settings.voxelSize) +
                                                         " (about " + std::to_string(levelsEstimate) + " voxels)");

    // Bin lists.
    std::unordered_map<std::uint64_t, std::size_t> binIndex;
    std::vector<std::pair<glm::ivec3, std::vector<std::uint32_t>>> bins;
    std::size_t references = 0;
    for (std::size_t i = 0; i < triangles.size(); ++i) {
        const PreparedTriangle t = source.bounds(triangles[i]);
        glm::ivec3 b0 = floorDiv(t.lo, kBin), b1 = floorDiv(t.hi, kBin);
        for (int x = b0.x; x <= b1.x; ++x)
            for (int y = b0.y; y <= b1.y; ++y)
                for (int z = b0.z; z <= b1.z; ++z) {
                    auto [it, inserted] = binIndex.try_emplace(binKey({x, y, z}), bins.size());
                    if (inserted) bins.push_back({glm::ivec3(x, y, z), {}});
                    bins[it->second].second.push_back(std::uint32_t(i));
                    ++references;
                }
    }
    // Big bins first so the last tasks are short.
    std::sort(bins.begin(), bins.end(), [](const auto& a, const auto& b) { return a.second.size() > b.second.size(); });

    std::vector<AccumLevel> perBin(bins.size());
    std::atomic<std::size_t> done{0}, tests{0};
    tbb::enumerable_thread_specific<BinScratch> scratch;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, bins.size(), 1), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t b = r.begin(); b != r.end(); ++b) {
            BinRasterizer rasterizer(bins[b].first, h, scratch.local());
            std::size_t localTests = 0;
            for (std::uint32_t t : bins[b].second) rasterizer.add(source.prepare(triangles[t]), localTests);
            rasterizer.collect(perBin[b]);
            tests += localTests;
            std::size_t now = done += bins[b].second.size();
            if (settings.progress) settings.progress(float(double(now) / double(std::max<std::size_t>(references, 1))));
        }
    });
    stats.overlapTests = tests;
    AccumLevel all;
    for (auto& level : perBin)
        for (auto& leaf : level) all.push_back(std::move(leaf));
    return all;
}

}  // namespace voxgi::detail
