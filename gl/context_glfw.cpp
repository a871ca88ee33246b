#include <epoxy/gl.h>
// After epoxy: GLFW must not pull in the system GL header.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "gl/context.h"

namespace voxgi::gl {

namespace {

class GlfwContext final : public Context {
public:
    explicit GlfwContext(GLFWwindow* window) : window_(window) {}
    ~GlfwContext() override {
        glfwDestroyWindow(window_);
        glfwTerminate();
    }
    void makeCurrent() override { glfwMakeContextCurrent(window_); }
    bool isWindow() const override { return true; }
    void swapBuffers() override { glfwSwapBuffers(window_); }
    void pollEvents() override { glfwPollEvents(); }
    bool shouldClose() const override { return glfwWindowShouldClose(window_) != 0; }
    void* nativeWindow() const override { return window_; }
    void setup(const ContextDesc& desc) { finishSetup(desc, "GLFW window"); }

private:
    GLFWwindow* window_;
};

}  // namespace

std::unique_ptr<Context> Context::createWindow(const ContextDesc& desc) {
    if (!glfwInit()) {
        const char* why = nullptr;
        glfwGetError(&why);
        throw GlError(std::string("cannot open a window (") + (why ? why : "no display") +
                      "); for images without a display use `voxgi render`");
    }
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, desc.debugOutput ? GLFW_TRUE : GLFW_FALSE);
    glfwWindowHint(GLFW_VISIBLE, desc.visible ? GLFW_TRUE : GLFW_FALSE);
    GLFWwindow* window = glfwCreateWindow(desc.width, desc.height, desc.title.c_str(), nullptr, nullptr);
    if (!window) {
        const char* why = nullptr;
        glfwGetError(&why);
        glfwTerminate();
        throw GlError(std::string("cannot create an OpenGL 4.5 core window (") + (why ? why : "unknown") + ")");
    }
    glfwMakeContextCurrent(window);
    auto context = std::make_unique<GlfwContext>(window);
    context->setup(desc);
    return context;
}

}  // namespace voxgi::gl
