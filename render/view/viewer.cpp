#include "render/view/viewer.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <algorithm>
#include <cstdint>
#include <set>
#include <filesystem>
#include <optional>
#include <vector>

#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include "gi/methods.h"
#include "gl/context.h"
#include "render/view/view_script.h"
#include "render/view/viewer_state.h"
#include "scenes/errors.h"
#include "scenes/image.h"
#include "scenes/sky_model.h"

namespace voxgi::view {

namespace {

// Auto exposure's time constant: a new view's exposure is 86 % there after two of them.
constexpr float kEyeAdaptationSeconds = 0.5f;

// The display and the debug drawings read the frame's textures whole, so the viewer draws no
// guard band (FrameOptions::guardBand): a method that asks for one gathers from the screen alone.
FrameOptions viewerFrameOptions() {
    FrameOptions o;
    o.guardBand = false;
    return o;
}

float radiusOf(const Scene& scene) {
    Bounds b = scene.bounds();
    return b.valid() ? std::max(0.5f * glm::length(b.extent()), 1e-6f) : 1.0f;
}

// The screenshot's EXR sits next to its PNG: shot.png -> shot.exr.
std::string exrPathFor(const std::string& png) {
    return std::filesystem::path(png).replace_extension(".exr").string();
}

// Switches to s.method; a setting the method refuses keeps the window alive and says why.
void switchMethod(ViewerState& s) {
    try {
        s.renderer->setMethod(s.method);
    } catch (const std::exception& e) {
        s.status = "cannot start " + s.method + ": " + e.what() + " (showing direct light)";
        std::fprintf(stderr, "voxgi view: %s\n", s.status.c_str());
        s.method = "direct";
        s.renderer->setMethod(s.method);
    }
    for (auto& [name, view] : s.methodViews) view.drawnFrame = -1000;
}

void saveScreenshot(ViewerState& s, const std::string& png) {
    Image image = s.renderer->resolve();
    image.display = {true, s.exposure, s.toneCurve};
    writeExr(exrPathFor(png), image);
    writePng(png, image, "beauty", s.exposure, s.toneCurve);
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
            auto renderer = std::make_unique<FrameRenderer>(s.scene, viewerFrameOptions(), s.method);
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
        switchMethod(s);
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

// What the technique draws of the views that are on; a view is redrawn every refreshFrames.
std::vector<DebugDrawing> methodDrawings(ViewerState& s) {
    std::vector<DebugDrawing> out;
    const GiTechnique* technique = s.renderer->technique();
    if (!technique) return out;
    for (const DebugViewInfo& info : findMethod(s.method).debugViews) {
        MethodView& view = s.methodViews[info.name];
        if (!view.on) continue;
        if (s.frame - view.drawnFrame >= info.refreshFrames || view.drawnFrame > s.frame) {
            try {
                view.drawing = technique->debugView(info.name, DebugViewContext{s.scene.camera, s.exposure, view.options});
            } catch (const std::exception& e) {
                view.drawing = {};
                s.status = info.label + ": " + e.what();
            }
            view.drawnFrame = s.frame;
        }
        out.push_back(view.drawing);
    }
    return out;
}

void runEvent(ViewerState& s, const ScriptEvent& e) {
    if (e.kind == "method") {
        findMethod(e.value);
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
      sceneRadius(radiusOf(s)), method(o.method), exposure(o.exposure), autoExposure(o.autoExposure),
      toneCurve(o.toneCurve), showPanel(o.panel) {
    speed = 0.5f * sceneRadius;
    debug.lights = o.panel;  // --no-panel: the bare picture
}

namespace {

// Every method's view of that name (views of one name share their meaning and options).
const DebugViewInfo* findView(const std::string& name) {
    for (const MethodInfo& m : methods())
        for (const DebugViewInfo& v : m.debugViews)
            if (v.name == name) return &v;
    return nullptr;
}

std::string showNames() {
    std::string names;
    for (int i = 0; i < kDisplayModeCount; ++i) names += std::string(displayModeName(DisplayMode(i))) + ", ";
    names += "voxels, voxels_blocker, bounds";
    std::set<std::string> seen;
    for (const MethodInfo& m : methods())
        for (const DebugViewInfo& v : m.debugViews)
            if (seen.insert(v.name).second) names += ", " + v.name + "[:option=value,...]";
    return names;
}

}  // namespace

void applyShow(ViewerState& s, const std::string& name) {
    for (int i = 0; i < kDisplayModeCount; ++i)
        if (name == displayModeName(DisplayMode(i))) {
            s.mode = DisplayMode(i);
            return;
        }
    if (name == "voxels" || name == "voxels_blocker") {
        s.debug.voxels = true;
        s.debug.voxelColor = name == "voxels" ? VoxelColor::Albedo : VoxelColor::Blocker;
        return;
    }
    if (name == "bounds") {
        s.debug.bounds = true;
        return;
    }
    // A method's view: NAME or NAME:option=value,option=value
    const std::size_t colon = name.find(':');
    const std::string viewName = name.substr(0, colon);
    const DebugViewInfo* info = findView(viewName);
    if (!info) throw InputError("show '" + name + "': expected " + showNames());
    GiSettings options;
    std::string rest = colon == std::string::npos ? "" : name.substr(colon + 1);
    for (std::size_t start = 0; start < rest.size();) {
        std::size_t end = std::min(rest.find(',', start), rest.size());
        const std::string assignment = rest.substr(start, end - start);
        const std::size_t eq = assignment.find('=');
        const SettingInfo* option = nullptr;
        for (const SettingInfo& o : info->options)
            if (eq != std::string::npos && o.key == viewName + "." + assignment.substr(0, eq)) option = &o;
        if (!option) throw InputError("show '" + name + "': '" + assignment + "' is not an option of " + viewName);
        validateSetting(*option, assignment.substr(eq + 1));
        options.set(option->key, assignment.substr(eq + 1));
        start = end + 1;
    }
    MethodView& view = s.methodViews[viewName];
    view.on = true;
    for (const auto& [key, value] : options.values()) view.options.set(key, value);
    view.drawnFrame = -1000;
}

bool toggleMethodView(ViewerState& s, char key) {
    bool any = false;
    for (const DebugViewInfo& info : findMethod(s.method).debugViews) {
        if (info.key != key) continue;
        MethodView& view = s.methodViews[info.name];
        view.on = !view.on;
        view.drawnFrame = -1000;
        any = true;
    }
    return any;
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
    s.renderer = std::make_unique<FrameRenderer>(scene, viewerFrameOptions(), s.method);
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
        // Fixed steps in --frames runs, so scripted captures and tests repeat exactly.
        const double step = options.frames > 0 ? 1.0 / 30.0 : double(seconds);
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
            s.animationTime += step;
            s.animator.apply(s.animationTime, scene.lights);
            s.viewChanged = true;
        }
        serveRequests(s);
        // A moved sun takes its sky along (an atmosphere's colours follow the sun's height).
        if (followSun(scene)) s.viewChanged = true;
        if (s.viewChanged) {
            s.renderer->resetAccumulation();
            s.viewChanged = false;
        }
        s.renderer->renderFrame();

        int fbw, fbh;
        glfwGetFramebufferSize(window, &fbw, &fbh);
        if (s.autoExposure) {
            // Eye adaptation: the exposure follows the picture with a time constant, so turning
            // the view does not make it flicker.
            if (const std::optional<float> target = s.display->autoExposureStops(*s.renderer, s.mode)) {
                s.exposure = s.exposureMeasured ? adaptExposure(s.exposure, *target, float(step), kEyeAdaptationSeconds)
                                                : *target;
                s.exposureMeasured = true;
            }
        }
        s.display->draw(*s.renderer, s.mode, s.exposure, s.toneCurve, fbw, fbh);
        s.overlay->draw(scene, s.debug, letterbox(s.renderer->width(), s.renderer->height(), fbw, fbh),
                        methodDrawings(s), s.renderer->textures().position);

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
