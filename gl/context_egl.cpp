// Headless contexts through EGL: Mesa's surfaceless platform first (llvmpipe, any Mesa driver),
// then the device platform (NVIDIA's EGL on machines without a display server).
#include <string>
#include <vector>

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include "gl/context.h"

namespace voxgi::gl {

namespace {

class EglContext final : public Context {
public:
    EglContext(EGLDisplay display, EGLContext context) : display_(display), context_(context) {}
    ~EglContext() override {
        eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(display_, context_);
        eglTerminate(display_);
    }
    void makeCurrent() override { eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_); }
    bool isWindow() const override { return false; }
    void setup(const ContextDesc& desc, const std::string& via) { finishSetup(desc, via); }

private:
    EGLDisplay display_;
    EGLContext context_;
};

bool hasClientExtension(const char* name) {
    return epoxy_has_egl_extension(EGL_NO_DISPLAY, name);
}

// Tries to make a GL 4.5 core context current on `display`; returns EGL_NO_CONTEXT on failure.
EGLContext tryContext(EGLDisplay display, bool debug, std::string& why) {
    EGLint major = 0, minor = 0;
    if (!eglInitialize(display, &major, &minor)) {
        why = "eglInitialize failed";
        return EGL_NO_CONTEXT;
    }
    if (!eglBindAPI(EGL_OPENGL_API)) {
        why = "EGL has no desktop OpenGL";
        eglTerminate(display);
        return EGL_NO_CONTEXT;
    }
    EGLConfig config = nullptr;
    EGLint count = 0;
    const EGLint configAttribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    bool noConfig = epoxy_has_egl_extension(display, "EGL_KHR_no_config_context");
    if (!eglChooseConfig(display, configAttribs, &config, 1, &count) || count == 0) {
        if (!noConfig) {
            why = "no EGL config with OpenGL";
            eglTerminate(display);
            return EGL_NO_CONTEXT;
        }
        config = nullptr;  // EGL_NO_CONFIG_KHR
    }
    const EGLint contextAttribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4,
                                     EGL_CONTEXT_MINOR_VERSION, 5,
                                     EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                     EGL_CONTEXT_OPENGL_DEBUG, debug ? EGL_TRUE : EGL_FALSE,
                                     EGL_NONE};
    EGLContext ctx = eglCreateContext(display, config, EGL_NO_CONTEXT, contextAttribs);
    if (ctx == EGL_NO_CONTEXT) {
        why = "the driver refused a GL 4.5 core context";
        eglTerminate(display);
        return EGL_NO_CONTEXT;
    }
    if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) {
        why = "surfaceless eglMakeCurrent failed";
        eglDestroyContext(display, ctx);
        eglTerminate(display);
        return EGL_NO_CONTEXT;
    }
    return ctx;
}

}  // namespace

std::unique_ptr<Context> Context::createHeadless(const ContextDesc& desc) {
    std::string reasons;
    auto attempt = [&](EGLDisplay display, const std::string& via) -> std::unique_ptr<Context> {
        if (display == EGL_NO_DISPLAY) {
            reasons += (reasons.empty() ? "" : "; ") + via + ": no display";
            return nullptr;
        }
        std::string why;
        EGLContext ctx = tryContext(display, desc.debugOutput, why);
        if (ctx == EGL_NO_CONTEXT) {
            reasons += (reasons.empty() ? "" : "; ") + via + ": " + why;
            return nullptr;
        }
        auto context = std::make_unique<EglContext>(display, ctx);
        context->setup(desc, via);
        return context;
    };
    if (hasClientExtension("EGL_MESA_platform_surfaceless")) {
        if (auto c = attempt(eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr),
                             "EGL surfaceless"))
            return c;
    }
    if (hasClientExtension("EGL_EXT_platform_device") && hasClientExtension("EGL_EXT_device_enumeration")) {
        EGLint count = 0;
        eglQueryDevicesEXT(0, nullptr, &count);
        std::vector<EGLDeviceEXT> devices(std::size_t(count > 0 ? count : 0));
        if (count > 0) eglQueryDevicesEXT(count, devices.data(), &count);
        for (EGLint i = 0; i < count; ++i) {
            if (auto c = attempt(eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[std::size_t(i)], nullptr),
                                 "EGL device " + std::to_string(i)))
                return c;
        }
    }
    throw GlError("cannot create a headless OpenGL 4.5 core context (" +
                  (reasons.empty() ? std::string("no EGL surfaceless or device platform") : reasons) + ")");
}

}  // namespace voxgi::gl
