// One interface over the two ways voxgi gets an OpenGL 4.5 core context: EGL without any
// window system (surfaceless platform, then the device platform) and a GLFW window.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>

namespace voxgi::gl {

// No usable GL 4.5 context, or a GL object failed (shader compile, incomplete framebuffer).
class GlError : public std::runtime_error {
public:
    explicit GlError(const std::string& message) : std::runtime_error(message) {}
};

struct ContextDesc {
    int width = 1280;          // window size (ignored headless)
    int height = 720;
    std::string title = "voxgi";
    bool debugOutput = true;   // route KHR_debug messages to the log
    bool visible = true;       // window back end only
};

class Context {
public:
    virtual ~Context() = default;
    virtual void makeCurrent() = 0;
    virtual bool isWindow() const = 0;
    // Window back end: presents, polls, and reports a close request. No-ops headless.
    virtual void swapBuffers() {}
    virtual void pollEvents() {}
    virtual bool shouldClose() const { return false; }
    virtual void* nativeWindow() const { return nullptr; }  // GLFWwindow* for the viewer

    // "llvmpipe (LLVM 15.0.6, 256 bits) / OpenGL 4.5 (Core Profile) Mesa 22.3.6 via EGL surfaceless"
    std::string description() const { return description_; }

    // Throws GlError with a one-line reason when no GL 4.5 core context can be made.
    static std::unique_ptr<Context> createHeadless(const ContextDesc& desc = {});
    static std::unique_ptr<Context> createWindow(const ContextDesc& desc = {});

protected:
    // Checks the version, installs debug output and fills description_; called once current.
    void finishSetup(const ContextDesc& desc, const std::string& via);
    std::string description_;
};

}  // namespace voxgi::gl
