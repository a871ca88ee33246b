// voxgi inspect: what a .vdb file holds, per grid (in the spirit of vdb_print), value
// histograms, and coloured slices to PNG.
#include <cmath>
#include <cstdio>
#include <algorithm>
#include <cstdlib>
#include <vector>

#include "scenes/errors.h"
#include "scenes/image.h"
#include "scenes/memory_limit.h"
#include "tools/commands.h"
#include "tools/scene_arg.h"
#include "volumes/geometry_volume.h"
#include "volumes/vdb_inspect.h"

namespace voxgi::cli {

namespace {

const char* kUsage =
    "voxgi inspect FILE.vdb [--stats [--bins N]] [--metadata] [--slice x|y|z=WORLD -o SLICE.png [--grid NAME]]\n"
    "  --stats: per-grid histogram of values (vector lengths for vector grids)\n"
    "  --slice: the voxel layer at a world coordinate, coloured (albedo in sRGB, vectors 0.5+0.5v,\n"
    "           scalars on a blue-red ramp); --grid picks the grid (default albedo, else the first);\n"
    "           voxels are drawn as squares so the image's longer side reaches --pixels (default 512)";

std::string formatBytes(std::uint64_t bytes) {
    char text[32];
    if (bytes >= (1ull << 20)) std::snprintf(text, sizeof text, "%.2f MiB", double(bytes) / double(1 << 20));
    else std::snprintf(text, sizeof text, "%.1f KiB", double(bytes) / 1024.0);
    return text;
}

void printGrids(const std::string& path, const VdbFileInfo& info, bool metadata) {
    std::printf("%s: %zu grid(s)\n", path.c_str(), info.grids.size());
    for (const auto& [key, value] : info.metadata)
        if (metadata || key.rfind("voxgi_", 0) == 0) std::printf("  %s = %s\n", key.c_str(), value.c_str());
    for (const VdbGridInfo& g : info.grids) {
        std::printf("%-16s %-6s class %-11s voxel %g", g.name.c_str(), g.valueType.c_str(), g.gridClass.c_str(),
                    g.voxelSize.x);
        if (g.voxelSize.y != g.voxelSize.x || g.voxelSize.z != g.voxelSize.x)
            std::printf("x%gx%g", g.voxelSize.y, g.voxelSize.z);
        std::printf("  active %llu", static_cast<unsigned long long>(g.activeVoxels));
        if (g.indexBox.empty()) {
            std::printf("  (empty)");
        } else {
            std::printf("  index [%d %d %d]..[%d %d %d]  world [%g %g %g]..[%g %g %g]", g.indexBox.min.x,
                        g.indexBox.min.y, g.indexBox.min.z, g.indexBox.max.x, g.indexBox.max.y, g.indexBox.max.z,
                        g.worldMin.x, g.worldMin.y, g.worldMin.z, g.worldMax.x, g.worldMax.y, g.worldMax.z);
        }
        std::printf("  memory %s\n", formatBytes(g.memoryBytes).c_str());
        if (metadata)
            for (const auto& [key, value] : g.metadata) std::printf("    %s = %s\n", key.c_str(), value.c_str());
    }
}

// voxgi keeps a geometry volume compact in memory (attributes for active voxels only), unlike
// the dense per-attribute grids the file lists; both sizes, so neither is mistaken for the other.
void printInMemorySize(const std::string& path, const VdbFileInfo& info) {
    const bool geometry = std::any_of(info.metadata.begin(), info.metadata.end(),
                                      [](const auto& m) { return m.first == "voxgi_levels"; });
    if (!geometry) return;
    std::uint64_t dense = 0;
    for (const VdbGridInfo& g : info.grids) dense += g.memoryBytes;
    try {
        SparseGeometryVolume volume = readGeometryVolume(path);
        std::printf("as a voxgi geometry volume: %s in memory (occupancy trees + compact attribute arrays), "
                    "%s as the dense grids above\n",
                    formatBytes(volume.memoryBytes()).c_str(), formatBytes(dense).c_str());
    } catch (const InputError& e) {
        std::printf("not loadable as a voxgi geometry volume: %s\n", e.what());
    }
}

void printHistograms(const std::vector<VdbHistogram>& histograms) {
    for (const VdbHistogram& h : histograms) {
        std::uint64_t total = 0, peak = 1;
        for (auto c : h.counts) total += c, peak = std::max(peak, c);
        std::printf("%s (%s, %llu active, range [%g, %g]):\n", h.grid.c_str(), h.quantity.c_str(),
                    static_cast<unsigned long long>(total), h.min, h.max);
        for (std::size_t b = 0; b < h.counts.size(); ++b) {
            double lo = h.min + (h.max - h.min) * double(b) / double(h.counts.size());
            double hi = h.min + (h.max - h.min) * double(b + 1) / double(h.counts.size());
            int bar = int(40 * h.counts[b] / peak);
            std::printf("  [%11.4g, %11.4g) %10llu %.*s\n", lo, hi, static_cast<unsigned long long>(h.counts[b]), bar,
                        "########################################");
        }
    }
}

int runInspect(const std::vector<std::string>& argv) {
    Args args(argv, {"--slice", "-o", "--grid", "--bins", "--pixels"}, {"--stats", "--metadata"});
    args.requirePositional(1, kUsage);
    const std::string path = args.positional()[0];
    const int bins = args.integer("--bins", 10, 1, 1000);
    auto sliceSpec = args.value("--slice");
    auto out = args.value("-o");
    if (sliceSpec && !out) throw InputError("--slice needs -o SLICE.png");
    if (out && !sliceSpec) throw InputError("-o is only used with --slice");
    int axis = -1;
    double world = 0.0;
    if (sliceSpec) {
        const std::string& s = *sliceSpec;
        char* end = nullptr;
        if (s.size() > 2 && s[1] == '=' && (s[0] == 'x' || s[0] == 'y' || s[0] == 'z')) {
            axis = s[0] - 'x';
            world = std::strtod(s.c_str() + 2, &end);
        }
        if (axis < 0 || !end || *end != '\0' || !std::isfinite(world))
            throw InputError("--slice: expected x=WORLD, y=WORLD or z=WORLD, got '" + s + "'");
        requireOutputs(args, {"-o"});
    }

    VdbFileInfo info = inspectVdbFile(path);
    printGrids(path, info, args.flag("--metadata"));
    printInMemorySize(path, info);
    if (args.flag("--stats")) printHistograms(vdbHistograms(path, bins));
    if (sliceSpec) {
        VdbSlice slice = sliceVdbFile(path, args.value("--grid", ""), axis, world);
        // Whole pixels per voxel, so that small grids stay readable.
        const int scale = std::max(1, args.integer("--pixels", 512, 1, 16384) / std::max(slice.width, slice.height));
        const std::size_t bytes = std::size_t(slice.width) * scale * std::size_t(slice.height) * scale * 3;
        // The image, stb's filtered copy of it and its deflate output: three times the pixels.
        requireMemory(3.0 * double(bytes), "--pixels " + std::to_string(slice.width * scale) + "x" +
                                               std::to_string(slice.height * scale) + " image");
        std::vector<std::uint8_t> rgb(bytes);
        for (int y = 0; y < slice.height * scale; ++y)
            for (int x = 0; x < slice.width * scale; ++x)
                for (int c = 0; c < 3; ++c)
                    rgb[(std::size_t(y) * std::size_t(slice.width * scale) + std::size_t(x)) * 3 + std::size_t(c)] =
                        slice.rgb[(std::size_t(y / scale) * std::size_t(slice.width) + std::size_t(x / scale)) * 3 + std::size_t(c)];
        writePngRgb8(*out, slice.width * scale, slice.height * scale, rgb);
        std::printf("wrote %s: grid %s, %c index %d, %dx%d voxels at %d pixel(s) each", out->c_str(), slice.grid.c_str(),
                    'x' + axis, slice.indexPlane, slice.width, slice.height, scale);
        if (slice.valueMax > slice.valueMin) std::printf(", ramp [%g, %g]", slice.valueMin, slice.valueMax);
        std::printf("\n");
    }
    return kOk;
}

}  // namespace

VOXGI_REGISTER_COMMAND("inspect", kUsage, runInspect);

}  // namespace voxgi::cli
