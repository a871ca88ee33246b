// voxgi dump: renders K frames of a scene with a GI method and writes that method's volumes
// as OpenVDB grids (`vdb_print`, Houdini, Blender and python-openvdb read them); with --sky, the
// scene's sky-lighting volume instead (no GL needed).
#include <cstdio>

#include "gi/methods.h"
#include "gi/raytrace/ray_tracer.h"
#include "gi/sky/sky_dump.h"
#include "gi/sky/sky_volume.h"
#include "gl/context.h"
#include "render/frame/frame_renderer.h"
#include "scenes/errors.h"
#include "tools/commands.h"
#include "tools/method_help.h"
#include "tools/scene_arg.h"

namespace voxgi::cli {

namespace {

const char* kUsage =
    "voxgi dump SCENE --method NAME [--frame K] -o OUT.vdb [--width W --height H] [--backend cpu|gl] [--set section.key=value]...\n"
    "voxgi dump SCENE --sky -o OUT.vdb [--set sky.KEY=VALUE]...\n"
    "  NAME: a method with volumes (default: the scene's gi.method)\n"
    "  --sky: the sky-lighting volume, grids sky_sh_{r,g,b}_0..8 (docs/sky.md)";

int runDump(const std::vector<std::string>& argv) {
    Args args(argv, {"--method", "-o", "--frame", "--width", "--height", "--set", "--backend"}, {"--sky"}, {"--set"});
    args.requirePositional(1, kUsage);
    auto out = args.value("-o");
    if (!out) throw InputError("-o OUT.vdb is required; usage: " + usageLine(kUsage));
    requireOutputs(args, {"-o"});
    const int frames = args.integer("--frame", 0, 0, 1 << 20) + 1;
    Scene scene = loadSceneArgument(args.positional()[0]);
    applySceneOverrides(args, scene);
    if (args.flag("--sky")) {
        if (args.has("--method")) throw InputError("--sky and --method: give one of them");
        if (!scene.sky.enabled) throw InputError("--sky: " + args.positional()[0] + " has no sky");
        const RayTracer tracer(scene);
        SkyVolume volume(tracer, readSkyVolumeDesc(scene.gi));
        volume.update();
        writeSkyVolumeVdb(*out, volume);
        const glm::ivec3 d = volume.dims(), b = volume.brickDims();
        std::printf("wrote %s (sky-lighting volume, %dx%dx%d cells of %g m; %zu of %d bricks of %d^3 cells stored, "
                    "%.2f MiB; %.0f ms)\n",
                    out->c_str(), d.x, d.y, d.z, double(volume.cellSize()), volume.activeBricks(), b.x * b.y * b.z,
                    SkyVolume::kBrickCells, double(volume.packed().size() * sizeof(glm::vec4)) / (1024.0 * 1024.0),
                    volume.buildMs());
        return kOk;
    }
    if (!args.has("--method") && scene.gi.getString("method", "").empty())
        throw InputError("--method NAME is required: " + args.positional()[0] + " names no gi.method");
    const std::string method = methodArgument(args, scene, "");
    if (!validateMethod(method, scene).create) throw InputError("--method " + method + " has no volumes to dump");
    auto context = gl::Context::createHeadless();
    FrameRenderer renderer(scene, FrameOptions{}, method);
    for (int f = 0; f < frames; ++f) renderer.renderFrame();
    renderer.technique()->dumpVdb(*out);
    std::printf("wrote %s (%s after %d frame(s))\n", out->c_str(), method.c_str(), frames);
    return kOk;
}

}  // namespace

VOXGI_REGISTER_COMMAND_WITH_DETAILS("dump", kUsage, runDump, methodList);

}  // namespace voxgi::cli
