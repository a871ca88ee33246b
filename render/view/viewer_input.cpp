// Keyboard and mouse for the viewer: the key bindings of docs/viewer.md, WASD + mouse look,
// and dragging the main light. ImGui gets the input first when its panel wants it.
#include <cmath>
#include <vector>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include "gi/methods.h"
#include "render/view/viewer_state.h"

namespace voxgi::view {

const char* const kViewerKeys = "WASDQEMLGBPVR";

namespace {

void cycleMethod(ViewerState& s) {
    std::vector<std::string> methods = builtMethods();
    for (std::size_t i = 0; i < methods.size(); ++i)
        if (methods[i] == s.method) {
            s.method = methods[(i + 1) % methods.size()];
            s.rebuildTechnique = true;
            return;
        }
    s.method = methods.front();
    s.rebuildTechnique = true;
}

void onKey(GLFWwindow* window, int key, int, int action, int mods) {
    auto* s = static_cast<ViewerState*>(glfwGetWindowUserPointer(window));
    if (!s || action != GLFW_PRESS || ImGui::GetIO().WantCaptureKeyboard) return;
    if (key == GLFW_KEY_ESCAPE) glfwSetWindowShouldClose(window, GLFW_TRUE);
    handleKey(*s, key, mods);
}

void onScroll(GLFWwindow* window, double, double dy) {
    auto* s = static_cast<ViewerState*>(glfwGetWindowUserPointer(window));
    if (!s || ImGui::GetIO().WantCaptureMouse) return;
    s->speed *= float(std::pow(1.2, dy));
}

}  // namespace

// Mouse look with the right button; Ctrl + left button drags the main light in the view plane.
void handleInput(GLFWwindow* window, ViewerState& s, float seconds) {
    PointerState& pointer = s.pointer;
    const ImGuiIO& io = ImGui::GetIO();
    bool moved = false;
    if (!io.WantCaptureKeyboard) {
        auto key = [&](int k) { return glfwGetKey(window, k) == GLFW_PRESS ? 1.0f : 0.0f; };
        MoveInput in;
        in.forward = key(GLFW_KEY_W) - key(GLFW_KEY_S);
        in.right = key(GLFW_KEY_D) - key(GLFW_KEY_A);
        in.up = key(GLFW_KEY_E) - key(GLFW_KEY_Q);
        float boost = key(GLFW_KEY_LEFT_SHIFT) > 0.0f ? 4.0f : 1.0f;
        moved = s.camera.move(in, s.speed * boost, seconds) || moved;
    }
    double x, y;
    glfwGetCursorPos(window, &x, &y);
    bool look = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
    bool drag = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS &&
                glfwGetKey(window, GLFW_KEY_LEFT_CONTROL) == GLFW_PRESS;
    if ((look || drag) && !io.WantCaptureMouse) {
        if (pointer.tracking) {
            float dx = float(x - pointer.x), dy = float(y - pointer.y);
            if (look) moved = s.camera.turn(0.003f * dx, -0.003f * dy) || moved;
            if (drag && !s.scene.lights.empty() && (dx != 0.0f || dy != 0.0f)) {
                glm::vec3 up = glm::cross(s.camera.right(), s.camera.forward());
                glm::vec3 offset = (dx * s.camera.right() - dy * up) * (s.sceneRadius / 300.0f);
                moveLight(s.scene.lights[0], offset, s.sceneRadius);
                s.animator.setRest(s.scene.lights);
                s.viewChanged = true;
            }
        }
        pointer.tracking = true;
    } else {
        pointer.tracking = false;
    }
    pointer.x = x;
    pointer.y = y;
    if (moved) {
        s.camera.applyTo(s.scene.camera);
        s.viewChanged = true;
    }
}


void installInputCallbacks(GLFWwindow* window, ViewerState& s) {
    glfwSetWindowUserPointer(window, &s);
    glfwSetKeyCallback(window, onKey);
    glfwSetScrollCallback(window, onScroll);
}

void handleKey(ViewerState& s, int key, int mods) {
    switch (key) {
        case GLFW_KEY_F1: s.showPanel = !s.showPanel; break;
        case GLFW_KEY_F2:
        case GLFW_KEY_P: s.takeScreenshot = true; break;
        case GLFW_KEY_F5: s.reloadShaders = true; break;
        case GLFW_KEY_R:
            if (mods & GLFW_MOD_CONTROL) s.reloadShaders = true;
            break;
        case GLFW_KEY_V: s.dumpVdb = true; break;
        case GLFW_KEY_M: cycleMethod(s); break;
        case GLFW_KEY_L: s.animateLights = !s.animateLights; break;
        case GLFW_KEY_G: s.debug.voxels = !s.debug.voxels; break;
        case GLFW_KEY_B: s.debug.bounds = !s.debug.bounds; break;
        case GLFW_KEY_1: case GLFW_KEY_2: case GLFW_KEY_3: case GLFW_KEY_4: case GLFW_KEY_5:
            s.mode = DisplayMode(key - GLFW_KEY_1);
            break;
        case GLFW_KEY_EQUAL: case GLFW_KEY_KP_ADD: s.speed *= 1.5f; break;
        case GLFW_KEY_MINUS: case GLFW_KEY_KP_SUBTRACT: s.speed /= 1.5f; break;
        default:
            // The rest of the letters belong to the method's debug views.
            if (key >= GLFW_KEY_A && key <= GLFW_KEY_Z) toggleMethodView(s, char('A' + (key - GLFW_KEY_A)));
            break;
    }
}

}  // namespace voxgi::view
