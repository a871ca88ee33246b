#include "render/view/viewer.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <unistd.h>
#include <vector>

#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include "render/frame/techniques.h"
#include "gl/context.h"
#include "render/view/view_script.h"
#include "render/view/viewer_state.h"
#include "scenes/errors.h"
#include "scenes/image.h"

namespace voxgi::view {

namespace {

float radiusOf(const Scene& scene) {
    Bounds b = scene.bounds();
    return b.valid() ? std::max(0.5f * glm::length(b.extent()), 1e-6f) : 1.0f;
}

// The screenshot's EXR sits next to its PNG: shot.png -> shot.exr.
std::string exrPathFor(const std::string& png) {
    return std::filesystem::path(png).replace_extension(".exr").string();
}

std::unique_ptr<GiTechnique> makeTechnique(ViewerState& s) {
    try {
        return createTechnique(s.method, s.scene);
    } catch (const std::exception& e) {
        // A setting the method refuses: keep the window alive and say why.
        s.status = "cannot start " + s.method + ": " + e.what() + " (showing direct light)";
        std::fprintf(stderr, "voxgi view: %s\n", s.status.c_str());
        s.method = "direct";
        return nullptr;
    }
}

void saveScreenshot(ViewerState& s, const std::string& png) {
    Image image = s.renderer->resolve();
    writeExr(exrPathFor(png), image);
    writePng(png, image, "beauty", s.exposure);
    s.status = "wrote " + png + " and " + exrPathFor(png);
    std::printf("%s\n", s.status.c_str());
    std::fflush(stdout);
}

std::string numberedPath(ViewerState& s, const char* extension) {
    char name[64];
    std::snprintf(name, sizeof(name), "voxgi-view-%03d%s", s.screenshotCount, extension);
    return (std::filesystem::path(s.options.outputDir) / name).string();
}

// What the window shows (back buffer, before the swap), as an 8-bit PNG rows top first.
// Dear ImGui for the window's lifetime, shut down on every exit path (its GLFW back end restores
// the callbacks it chained).
class ImGuiSession {
public:
    explicit ImGuiSession(GLFWwindow* window) : window_(window) {
        IMGUI_CHECKVERSION();
        ImGui::CreateContext();
        ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini in the user's folder
        ImGui_ImplGlfw_InitForOpenGL(window, true);  // chains to the callbacks installed before
        ImGui_ImplOpenGL3_Init("#version 450 core");
    }
    ~ImGuiSession() {
        ImGui_ImplOpenGL3_Shutdown();
        ImGui_ImplGlfw_Shutdown();
        ImGui::DestroyContext();
        glfwSetWindowUserPointer(window_, nullptr);
    }
    ImGuiSession(const ImGuiSession&) = delete;
    ImGuiSession& operator=(const ImGuiSession&) = delete;

private:
    GLFWwindow* window_;
};

void captureWindow(const std::string& path, int width, int height) {
    std::vector<std::uint8_t> bottomUp(std::size_t(width) * std::size_t(height) * 3);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glReadBuffer(GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, bottomUp.data());
    std::vector<std::uint8_t> rgb(bottomUp.size());
    std::size_t row = std::size_t(width) * 3;
    for (int y = 0; y < height; ++y)
        std::copy_n(&bottomUp[std::size_t(height - 1 - y) * row], row, &rgb[std::size_t(y) * row]);
    writePngRgb8(path, width, height, rgb);
}

void serveRequests(ViewerState& s) {
    if (s.reloadShaders) {
        s.reloadShaders = false;
        try {
            // Shaders are compiled in the constructors: rebuilding them re-reads shaders/.
            auto renderer = std::make_unique<FrameRenderer>(s.scene, FrameOptions{}, createTechnique(s.method, s.scene));
            auto display = std::make_unique<DisplayPass>();
            auto overlay = std::make_unique<DebugOverlay>();
            s.renderer = std::move(renderer);
            s.display = std::move(display);
            s.overlay = std::move(overlay);
            s.status = "shaders reloaded";
        } catch (const std::exception& e) {
            s.status = std::string("reload failed, kept the old shaders: ") + e.what();
        }
        std::printf("%s\n", s.status.c_str());
    }
    if (s.rebuildTechnique) {
        s.rebuildTechnique = false;
        s.renderer->setTechnique(makeTechnique(s));
    }
    if (s.takeScreenshot) {
        s.takeScreenshot = false;
        try {
            saveScreenshot(s, numberedPath(s, ".png"));
            ++s.screenshotCount;
        } catch (const std::exception& e) {
            // A key press must not end the session (e.g. --out-dir not writable).
            s.status = std::string("screenshot failed: ") + e.what();
            std::fprintf(stderr, "voxgi view: %s\n", s.status.c_str());
        }
    }
    if (s.dumpVdb) {
        s.dumpVdb = false;
        if (GiTechnique* t = s.renderer->technique()) {
            std::string path = numberedPath(s, ("-" + s.method + ".vdb").c_str());
            try {
                t->dumpVdb(path);
                s.status = "wrote " + path;
                ++s.screenshotCount;
            } catch (const std::exception& e) {
                s.status = std::string("dump failed: ") + e.what();
            }
        } else {
            s.status = "direct light has no GI state to dump";
        }
        std::printf("%s\n", s.status.c_str());
    }
}

SphereSet debugSpheres(ViewerState& s) {
    SphereSet spheres;
    if (s.debug.probes) spheres = ddgiProbeSpheres(s.renderer->technique(), s.debug.probeColor, s.exposure);
    if (!s.debug.lpvCells) return spheres;
    // Reading the light volume back costs a dump: every 8 frames is enough to watch it settle.
    if (s.frame - s.lpvSpheresFrame >= 8 || s.lpvSpheresFrame > s.frame) {
        try {
            std::string scratch = (std::filesystem::temp_directory_path() /
                                   ("voxgi-view-lpv-" + std::to_string(::getpid()) + ".vdb")).string();
            s.lpvSpheres = lpvCellSpheres(s.renderer->technique(), s.debug.lpvCascade, s.debug.lpvStride, s.exposure, scratch);
        } catch (const std::exception& e) {
            s.lpvSpheres = {};
            s.status = std::string("light volume view: ") + e.what();
        }
        s.lpvSpheresFrame = s.frame;
    }
    return spheres.spheres.empty() ? s.lpvSpheres : spheres;
}

void runEvent(ViewerState& s, const ScriptEvent& e) {
    if (e.kind == "method") {
        validateMethod(e.value);
        s.method = e.value;
        s.rebuildTechnique = true;
    } else if (e.kind == "show") {
        applyShow(s, e.value);
    } else if (e.value == "screenshot") {
        s.takeScreenshot = true;
    } else if (e.value == "dump") {
        s.dumpVdb = true;
    } else if (e.value == "reload") {
        s.reloadShaders = true;
    } else if (e.value == "animate_lights") {
        s.animateLights = !s.animateLights;
    }
}

}  // namespace

ViewerState::ViewerState(Scene& s, const ViewerOptions& o)
    : scene(s), options(o), camera(s.camera), animator(s.lights, s.camera.up, radiusOf(s)),
      sceneRadius(radiusOf(s)), method(o.method), exposure(o.exposure), showPanel(o.panel) {
    speed = 0.5f * sceneRadius;
    debug.lights = o.panel;  // --no-panel: the bare picture
}

void applyShow(ViewerState& s, const std::string& name) {
    for (int i = 0; i < kDisplayModeCount; ++i)
        if (name == displayModeName(DisplayMode(i))) {
            s.mode = DisplayMode(i);
            return;
        }
    if (name == "voxels" || name == "voxels_blocker") {
        s.debug.voxels = true;
        s.debug.voxelColor = name == "voxels" ? VoxelColor::Albedo : VoxelColor::Blocker;
    } else if (name == "bounds") {
        s.debug.bounds = true;
    } else if (name == "cascades") {
        s.debug.cascades = true;
    } else if (name.rfind("lpv_cells", 0) == 0) {
        // lpv_cells or lpv_cells_N (cascade N)
        s.debug.lpvCells = true;
        s.debug.lpvCascade = name.size() > 10 ? std::atoi(name.c_str() + 10) : 0;
        s.lpvSpheresFrame = -1000;
    } else if (name == "probes" || name == "probe_states") {
        s.debug.probes = true;
        s.debug.probeColor = name == "probes" ? ProbeColor::Irradiance : ProbeColor::State;
    } else {
        throw InputError("show '" + name + "': expected beauty, direct, indirect, albedo, normal, voxels, "
                         "voxels_blocker, bounds, cascades, lpv_cells[_N], probes or probe_states");
    }
}

bool displayAvailable() {
    const char* x11 = std::getenv("DISPLAY");
    const char* wayland = std::getenv("WAYLAND_DISPLAY");
    return (x11 && *x11) || (wayland && *wayland);
}

int runViewer(Scene& scene, const ViewerOptions& options) {
    if (!displayAvailable())
        throw gl::GlError("no display (DISPLAY is not set): the viewer needs a window; for images use `voxgi render`");
    std::unique_ptr<ViewScript> script;
    if (!options.script.empty()) script = std::make_unique<ViewScript>(ViewScript::load(options.script));

    gl::ContextDesc desc;
    // Room for the panel beside a small render; the render is letterboxed.
    desc.width = options.windowWidth > 0 ? options.windowWidth : std::max(scene.camera.width, 1280);
    desc.height = options.windowHeight > 0 ? options.windowHeight : std::max(scene.camera.height, 720);
    desc.title = "voxgi view";
    desc.debugOutput = false;
    auto context = gl::Context::createWindow(desc);
    auto* window = static_cast<GLFWwindow*>(context->nativeWindow());
    glfwSwapInterval(options.frames > 0 ? 0 : 1);
    std::printf("voxgi view: %s\n", context->description().c_str());
    std::fflush(stdout);

    ViewerState s(scene, options);
    // A setting the method refuses at start is an input error (exit 2), as in `voxgi render`.
    s.renderer = std::make_unique<FrameRenderer>(scene, FrameOptions{}, createTechnique(s.method, scene));
    s.display = std::make_unique<DisplayPass>();
    s.overlay = std::make_unique<DebugOverlay>();

    installInputCallbacks(window, s);
    ImGuiSession imgui(window);

    auto last = std::chrono::steady_clock::now();
    while (!context->shouldClose() && (options.frames <= 0 || s.frame < options.frames)) {
        context->pollEvents();
        auto now = std::chrono::steady_clock::now();
        float seconds = std::chrono::duration<float>(now - last).count();
        last = now;
        s.frameMs = 1000.0 * double(seconds);

        if (script) {
            for (const ScriptEvent& e : script->eventsAt(s.frame)) runEvent(s, e);
            Camera before = scene.camera;
            script->apply(s.frame, scene.camera);
            if (before.eye != scene.camera.eye || before.target != scene.camera.target) {
                s.camera = FlyCamera(scene.camera);
                s.viewChanged = true;
            }
        } else if (options.frames <= 0) {
            handleInput(window, s, seconds);
        }
        if (s.animateLights) {
            // Fixed steps in --frames runs, so scripted captures and tests repeat exactly.
            s.animationTime += options.frames > 0 ? 1.0 / 30.0 : double(seconds);
            s.animator.apply(s.animationTime, scene.lights);
            s.viewChanged = true;
        }
        serveRequests(s);
        if (s.viewChanged) {
            s.renderer->resetAccumulation();
            s.viewChanged = false;
        }
        s.renderer->renderFrame();

        int fbw, fbh;
        glfwGetFramebufferSize(window, &fbw, &fbh);
        s.display->draw(*s.renderer, s.mode, s.exposure, fbw, fbh);
        s.overlay->draw(scene, s.debug, letterbox(s.renderer->width(), s.renderer->height(), fbw, fbh),
                        debugSpheres(s), s.debug.cascades ? cascadeBoxes(s.renderer->technique(), scene.bounds(), scene.camera)
                                                          : std::vector<DebugBox>{},
                        s.renderer->textures().position);

        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        ImGui::NewFrame();
        if (s.showPanel) drawPanel(s);
        ImGui::Render();
        ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
        bool lastFrame = options.frames > 0 && s.frame + 1 == options.frames;
        if (!options.windowCapture.empty() && (lastFrame || context->shouldClose())) captureWindow(options.windowCapture, fbw, fbh);
        context->swapBuffers();
        ++s.frame;
    }
    if (!options.screenshot.empty()) saveScreenshot(s, options.screenshot);
    return 0;
}

}  // namespace voxgi::view
