// voxgi view: the fly camera and camera scripts (pure math), the no-display message, and the
// window itself under X: N frames then a screenshot equal to `voxgi render` of the same view,
// a scripted camera path whose moves restart the accumulation, and the on-screen tone mapping
// equal to the PNG writer's.
#include <gtest/gtest.h>

#include <cmath>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <thread>

#include <stb/stb_image.h>
#include <sys/wait.h>
#include <unistd.h>

#include "gi/methods.h"
#include "gl/context.h"
#include "render/frame/frame_renderer.h"
#include "render/view/fly_camera.h"
#include "render/view/light_controls.h"
#include "render/view/view_script.h"
#include "render/view/viewer_state.h"
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include "scenes/errors.h"
#include "scenes/image.h"
#include "shaders/shared/constants.h"
#include "support/test_support.h"

namespace voxgi {
namespace {

using test::runVoxgi;

// ---- fly camera ----

TEST(FlyCamera, StartsLookingWhereTheSceneCameraLooks) {
    Camera cam;
    cam.eye = {1, 2, 3};
    cam.target = {1, 2, 0};
    view::FlyCamera fly(cam);
    EXPECT_NEAR(fly.forward().z, -1.0f, 1e-6f);
    Camera out = cam;
    fly.applyTo(out);
    glm::vec3 dir = glm::normalize(out.target - out.eye);
    EXPECT_NEAR(glm::length(dir - glm::vec3(0, 0, -1)), 0.0f, 1e-6f);
    // Same view matrix as before: the target may move along the ray, nothing else.
    glm::mat4 a = cam.view(), b = out.view();
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) EXPECT_NEAR(a[c][r], b[c][r], 1e-5f);
}

TEST(FlyCamera, MovesSpeedTimesSecondsAlongTheViewBasis) {
    Camera cam;
    cam.eye = {0, 0, 0};
    cam.target = {0, 0, -1};
    view::FlyCamera fly(cam);
    EXPECT_TRUE(fly.move({1.0f, 0.0f, 0.0f}, 2.0f, 0.5f));  // W for 0.5 s at 2 units/s
    EXPECT_NEAR(glm::length(fly.eye() - glm::vec3(0, 0, -1)), 0.0f, 1e-6f);
    EXPECT_TRUE(fly.move({0.0f, 1.0f, 0.0f}, 1.0f, 1.0f));  // D: right is +x looking down -z
    EXPECT_NEAR(glm::length(fly.eye() - glm::vec3(1, 0, -1)), 0.0f, 1e-6f);
    EXPECT_TRUE(fly.move({0.0f, 0.0f, 1.0f}, 1.0f, 1.0f));  // E: up
    EXPECT_NEAR(fly.eye().y, 1.0f, 1e-6f);
    EXPECT_FALSE(fly.move({}, 1.0f, 1.0f));
}

TEST(FlyCamera, TurnsRightWithPositiveYawAndClampsPitch) {
    Camera cam;
    cam.eye = {0, 0, 0};
    cam.target = {0, 0, -1};
    view::FlyCamera fly(cam);
    fly.turn(0.5f * shading::kPi, 0.0f);
    EXPECT_NEAR(glm::length(fly.forward() - glm::vec3(1, 0, 0)), 0.0f, 1e-5f);
    fly.turn(0.0f, 10.0f);  // far past straight up
    EXPECT_NEAR(std::asin(fly.forward().y), glm::radians(89.0f), 1e-4f);
    EXPECT_FALSE(fly.turn(0.0f, 1.0f));  // already at the limit
    Camera out = cam;
    fly.applyTo(out);
    EXPECT_TRUE(std::isfinite(out.view()[0][0]));
}

// ---- camera script ----

TEST(ViewScript, InterpolatesBetweenKeysAndHoldsTheEnds) {
    auto script = view::ViewScript::fromKeys({{10, {0, 0, 0}, {0, 0, -1}}, {20, {10, 0, 0}, {10, 0, -1}}});
    Camera cam;
    script.apply(0, cam);
    EXPECT_FLOAT_EQ(cam.eye.x, 0.0f);
    script.apply(15, cam);
    EXPECT_FLOAT_EQ(cam.eye.x, 5.0f);
    EXPECT_FLOAT_EQ(cam.target.x, 5.0f);
    script.apply(20, cam);
    EXPECT_FLOAT_EQ(cam.eye.x, 10.0f);
    script.apply(99, cam);
    EXPECT_FLOAT_EQ(cam.eye.x, 10.0f);
}

TEST(ViewScript, RejectsBadFilesWithTheFileName) {
    std::string dir = test::makeTempDir("view-script");
    auto expectError = [&](const std::string& text, const std::string& fragment) {
        std::string path = dir + "/s.json";
        test::writeFile(path, text);
        try {
            view::ViewScript::load(path);
            ADD_FAILURE() << "accepted: " << text;
        } catch (const InputError& e) {
            std::string what = e.what();
            EXPECT_NE(what.find(path), std::string::npos) << what;
            EXPECT_NE(what.find(fragment), std::string::npos) << what;
        }
    };
    expectError("{", "invalid JSON");
    expectError("{\"keys\": []}", "no camera keys");
    expectError("{\"keys\": [{\"frame\": 0, \"eye\": [0,0], \"target\": [0,0,1]}]}", "'eye'");
    expectError("{\"keys\": [{\"frame\": 3, \"eye\": [0,0,0], \"target\": [0,0,1]},"
                " {\"frame\": 3, \"eye\": [1,0,0], \"target\": [0,0,1]}]}",
                "larger than");
    EXPECT_THROW(view::ViewScript::load(dir + "/absent.json"), InputError);
}

// ---- keys ----

TEST(ViewerKeys, KeysRequestTheDocumentedActions) {
    Scene scene = test::cornellBox();
    view::ViewerOptions options;
    options.method = "direct";
    view::ViewerState s(scene, options);
    view::handleKey(s, GLFW_KEY_M, 0);
    EXPECT_EQ(s.method, builtMethods()[1]);
    EXPECT_TRUE(s.rebuildTechnique);
    for (std::size_t i = 1; i < builtMethods().size(); ++i) view::handleKey(s, GLFW_KEY_M, 0);
    EXPECT_EQ(s.method, "direct");  // M cycles through every built method
    view::handleKey(s, GLFW_KEY_3, 0);
    EXPECT_EQ(s.mode, view::DisplayMode::Indirect);
    view::handleKey(s, GLFW_KEY_5, 0);
    EXPECT_EQ(s.mode, view::DisplayMode::Normal);
    view::handleKey(s, GLFW_KEY_P, 0);
    EXPECT_TRUE(s.takeScreenshot);
    view::handleKey(s, GLFW_KEY_V, 0);
    EXPECT_TRUE(s.dumpVdb);
    view::handleKey(s, GLFW_KEY_R, 0);
    EXPECT_FALSE(s.reloadShaders);  // plain R is nothing (close to the movement keys)
    view::handleKey(s, GLFW_KEY_R, GLFW_MOD_CONTROL);
    EXPECT_TRUE(s.reloadShaders);
    view::handleKey(s, GLFW_KEY_L, 0);
    EXPECT_TRUE(s.animateLights);
    float speed = s.speed;
    view::handleKey(s, GLFW_KEY_EQUAL, 0);
    EXPECT_FLOAT_EQ(s.speed, 1.5f * speed);
    for (int key : {GLFW_KEY_G, GLFW_KEY_B}) view::handleKey(s, key, 0);
    EXPECT_TRUE(s.debug.voxels && s.debug.bounds);
    // Other letters toggle the current method's views, as the method declares them.
    view::handleKey(s, GLFW_KEY_H, 0);
    EXPECT_FALSE(s.methodViews["lpv_cells"].on) << "direct has no LPV cells";
    s.method = "lpv";
    for (int key : {GLFW_KEY_C, GLFW_KEY_H}) view::handleKey(s, key, 0);
    EXPECT_TRUE(s.methodViews["cascades"].on && s.methodViews["lpv_cells"].on);
    s.method = "ddgi";
    view::handleKey(s, GLFW_KEY_O, 0);
    EXPECT_TRUE(s.methodViews["probes"].on);
    view::handleKey(s, GLFW_KEY_C, 0);
    EXPECT_FALSE(s.methodViews["cascades"].on) << "C toggles the bounds view back off";
}

// A method's view keys are letters the viewer leaves free, one view per key within a method.
TEST(ViewerKeys, MethodViewKeysDoNotCollide) {
    for (const MethodInfo& m : methods()) {
        std::string used;
        for (const DebugViewInfo& v : m.debugViews) {
            if (!v.key) continue;
            EXPECT_TRUE(v.key >= 'A' && v.key <= 'Z') << m.name << " " << v.name;
            EXPECT_EQ(std::string(view::kViewerKeys).find(v.key), std::string::npos) << m.name << " " << v.name;
            EXPECT_EQ(used.find(v.key), std::string::npos) << m.name << " " << v.name;
            used += v.key;
        }
    }
}

// Script `show` events reach a method's views with their options, checked against the view's
// declaration.
TEST(ViewerShow, MethodViewsWithOptions) {
    Scene scene = test::cornellBox();
    view::ViewerOptions options;
    options.method = "clpv";
    view::ViewerState s(scene, options);
    view::applyShow(s, "lpv_cells:cascade=2,stride=3");
    EXPECT_TRUE(s.methodViews["lpv_cells"].on);
    EXPECT_EQ(s.methodViews["lpv_cells"].options.getString("lpv_cells.cascade", ""), "2");
    EXPECT_EQ(s.methodViews["lpv_cells"].options.getString("lpv_cells.stride", ""), "3");
    view::applyShow(s, "probes:color=state");
    EXPECT_EQ(s.methodViews["probes"].options.getString("probes.color", ""), "state");
    view::applyShow(s, "cascades");
    EXPECT_TRUE(s.methodViews["cascades"].on);
    EXPECT_THROW(view::applyShow(s, "lpv_cells:cascade=9"), InputError);  // outside [0, 5]
    EXPECT_THROW(view::applyShow(s, "lpv_cells:colour=red"), InputError);
    EXPECT_THROW(view::applyShow(s, "probes:color=pink"), InputError);
    EXPECT_THROW(view::applyShow(s, "no_such_view"), InputError);
}

// ---- light controls ----

TEST(LightControls, DragMovesPositionsAndTiltsSuns) {
    Light point;
    point.position = {1, 2, 3};
    view::moveLight(point, {0.5f, 0, 0}, 10.0f);
    EXPECT_FLOAT_EQ(point.position.x, 1.5f);
    Light sun;
    sun.type = LightType::Directional;
    sun.direction = {0, -1, 0};
    view::moveLight(sun, {1.0f, 0, 0}, 10.0f);
    EXPECT_NEAR(glm::length(sun.direction), 1.0f, 1e-6f);
    EXPECT_GT(sun.direction.x, 0.0f);
}

TEST(LightControls, AnimationCirclesTheRestPositionAndLoops) {
    Light point;
    point.position = {0, 1, 0};
    std::vector<Light> lights{point};
    view::LightAnimator animator(lights, {0, 1, 0}, 2.0f, 4.0f);
    animator.apply(1.0, lights);
    glm::vec3 offset = lights[0].position - point.position;
    EXPECT_NEAR(glm::length(offset), 0.3f, 1e-5f);  // 15% of the scene radius
    EXPECT_NEAR(offset.y, 0.0f, 1e-6f);             // in the plane normal to up
    std::vector<Light> again{point};
    animator.apply(5.0, again);                     // one period later
    EXPECT_NEAR(glm::length(again[0].position - lights[0].position), 0.0f, 1e-5f);
}

// ---- debug-view data (headless GL) ----

bool inside(glm::vec3 p, const DebugBox& box, float slack) {
    return glm::all(glm::greaterThanEqual(p, box.min - slack)) && glm::all(glm::lessThanEqual(p, box.max + slack));
}

DebugDrawing drawView(FrameRenderer& renderer, const std::string& view, const Camera& camera,
                      const GiSettings& options = {}) {
    return renderer.technique()->debugView(view, DebugViewContext{camera, 0.0f, options});
}

// The LPV cell spheres come from the technique's light volume: inside the cascade box, and the
// colour bleeding is on the right side (more red than green near the red wall at x = 0.55,
// the reverse near the green wall at x = 0).
TEST(DebugViewData, LpvCellsSitInTheCascadeAndCarryColourBleeding) {
    auto context = gl::Context::createHeadless();
    Scene scene = test::cornellBox();
    scene.camera.width = scene.camera.height = 64;
    FrameRenderer renderer(scene, FrameOptions{}, "lpv");
    renderer.renderFrame();
    std::vector<DebugBox> boxes = drawView(renderer, "cascades", scene.camera).boxes;
    ASSERT_EQ(boxes.size(), 1u);
    GiSettings everyCell;
    everyCell.set("lpv_cells.stride", "1");
    DebugDrawing set = drawView(renderer, "lpv_cells", scene.camera, everyCell);
    ASSERT_FALSE(set.spheres.empty());
    EXPECT_TRUE(set.shSpheres);
    glm::vec3 nearRed(0.0f), nearGreen(0.0f);
    for (const DebugSphere& s : set.spheres) {
        glm::vec3 c(s.centerRadius);
        EXPECT_TRUE(inside(c, boxes[0], 1e-4f)) << c.x << " " << c.y << " " << c.z;
        glm::vec3 mean(s.r.x, s.g.x, s.b.x);
        if (c.x > 0.45f && c.y > 0.1f && c.y < 0.45f) nearRed += mean;
        if (c.x < 0.1f && c.y > 0.1f && c.y < 0.45f) nearGreen += mean;
    }
    EXPECT_GT(nearRed.r / nearRed.g, nearGreen.r / nearGreen.g);
    EXPECT_GT(nearGreen.g / nearGreen.r, nearRed.g / nearRed.r);
    // A view the technique does not declare draws nothing.
    EXPECT_TRUE(drawView(renderer, "probes", scene.camera).spheres.empty());
}

// The stored bricks: as many boxes as the technique reports (fewer than the grid has), each
// inside its cascade and at most 8 cells wide.
TEST(DebugViewData, LpvBricksAreTheStoredBricksInsideTheCascade) {
    auto context = gl::Context::createHeadless();
    Scene scene = test::cornellBox();
    scene.camera.width = scene.camera.height = 32;
    scene.gi.set("lpv.resolution", "32");
    FrameRenderer renderer(scene, FrameOptions{}, "lpv");
    renderer.renderFrame();
    const DebugBox cascade = drawView(renderer, "cascades", scene.camera).boxes.at(0);
    const std::vector<DebugBox> bricks = drawView(renderer, "lpv_bricks", scene.camera).boxes;
    double stored = 0.0, grid = 0.0;
    for (const TechniqueStat& st : renderer.technique()->stats()) {
        if (st.name == "light_bricks") stored = st.value;
        if (st.name == "grid_bricks") grid = st.value;
    }
    EXPECT_EQ(double(bricks.size()), stored);
    EXPECT_LT(stored, grid);
    const float cell = (cascade.max.x - cascade.min.x) / 32.0f;
    for (const DebugBox& b : bricks) {
        EXPECT_TRUE(inside(b.min, cascade, 1e-4f) && inside(b.max, cascade, 1e-4f));
        EXPECT_LE(b.max.x - b.min.x, 8.0f * cell * 1.0001f);
    }
}

TEST(DebugViewData, ClpvShowsNestedCascades) {
    auto context = gl::Context::createHeadless();
    Scene scene = test::cornellBox();
    scene.camera.width = scene.camera.height = 64;
    FrameRenderer renderer(scene, FrameOptions{}, "clpv");
    renderer.renderFrame();
    std::vector<DebugBox> boxes = drawView(renderer, "cascades", scene.camera).boxes;
    ASSERT_GE(boxes.size(), 2u);
    for (std::size_t i = 1; i < boxes.size(); ++i) {
        glm::vec3 fine = boxes[i - 1].max - boxes[i - 1].min, coarse = boxes[i].max - boxes[i].min;
        EXPECT_NEAR(coarse.x / fine.x, 2.0f, 1e-3f) << "cascade " << i;  // cell size doubles per cascade
    }
    // Every cascade's cells lie in its box.
    for (std::size_t c = 0; c < boxes.size(); ++c) {
        GiSettings options;
        options.set("lpv_cells.cascade", std::to_string(c));
        DebugDrawing set = drawView(renderer, "lpv_cells", scene.camera, options);
        for (const DebugSphere& s : set.spheres)
            EXPECT_TRUE(inside(glm::vec3(s.centerRadius), boxes[c], 1e-4f)) << "cascade " << c;
    }
}

// One sphere per DDGI probe, inside its probe volume (relocation moves a probe < 0.45 cells);
// state colours are the three fixed ones.
TEST(DebugViewData, DdgiProbesOnePerProbeInsideTheVolume) {
    auto context = gl::Context::createHeadless();
    Scene scene = test::cornellBox();
    scene.camera.width = scene.camera.height = 64;
    scene.gi.set("ddgi.rays", "32");
    FrameRenderer renderer(scene, FrameOptions{}, "ddgi");
    renderer.renderFrame();
    std::vector<DebugBox> boxes = drawView(renderer, "cascades", scene.camera).boxes;
    ASSERT_EQ(boxes.size(), 1u);
    GiSettings byState;
    byState.set("probes.color", "state");
    DebugDrawing lit = drawView(renderer, "probes", scene.camera);
    DebugDrawing states = drawView(renderer, "probes", scene.camera, byState);
    ASSERT_FALSE(lit.spheres.empty());
    ASSERT_EQ(lit.spheres.size(), states.spheres.size());
    float slack = 0.5f * glm::length(boxes[0].max - boxes[0].min);  // generous: relocation only
    double brightness = 0.0;
    for (std::size_t i = 0; i < lit.spheres.size(); ++i) {
        EXPECT_TRUE(inside(glm::vec3(lit.spheres[i].centerRadius), boxes[0], slack));
        brightness += lit.spheres[i].r.x + lit.spheres[i].g.x + lit.spheres[i].b.x;
        glm::vec3 c(states.spheres[i].r.x, states.spheres[i].g.x, states.spheres[i].b.x);
        bool known = c == glm::vec3(0.2f, 0.9f, 0.2f) || c == glm::vec3(0.2f, 0.4f, 1.0f) || c == glm::vec3(0.9f, 0.15f, 0.1f);
        EXPECT_TRUE(known);
    }
    EXPECT_GT(brightness, 0.0) << "all probes black after a frame";
    EXPECT_TRUE(drawView(renderer, "lpv_cells", scene.camera).spheres.empty());
}

// ---- the window ----

// Gives the test process an X display: the one it has, else a private Xvfb it starts (and
// stops at exit), so the window tests run (never skip) with or without xvfb-run.
class XDisplay : public ::testing::Environment {
public:
    void SetUp() override {
        const char* display = std::getenv("DISPLAY");
        if (display && *display) return;
        for (int n = 90 + int(getpid() % 200); n < 400; ++n) {
            std::string lock = "/tmp/.X" + std::to_string(n) + "-lock";
            if (std::filesystem::exists(lock)) continue;
            pid_t pid = fork();
            if (pid == 0) {
                std::string name = ":" + std::to_string(n);
                execlp("Xvfb", "Xvfb", name.c_str(), "-screen", "0", "1280x1024x24", "-nolisten", "tcp",
                       static_cast<char*>(nullptr));
                _exit(127);
            }
            std::string socket = "/tmp/.X11-unix/X" + std::to_string(n);
            for (int i = 0; i < 100 && !std::filesystem::exists(socket); ++i)
                std::this_thread::sleep_for(std::chrono::milliseconds(50));
            // Two tests may race for one display number: the loser's Xvfb exits at once, so
            // ours must still be running once the socket is there.
            std::this_thread::sleep_for(std::chrono::milliseconds(150));
            bool ours = waitpid(pid, nullptr, WNOHANG) == 0;
            if (std::filesystem::exists(socket) && ours) {
                xvfb_ = pid;
                setenv("DISPLAY", (":" + std::to_string(n)).c_str(), 1);
                return;
            }
            if (ours) {
                kill(pid, SIGTERM);
                waitpid(pid, nullptr, 0);
            }
        }
    }
    void TearDown() override {
        if (xvfb_ <= 0) return;
        kill(xvfb_, SIGTERM);
        waitpid(xvfb_, nullptr, 0);
        unsetenv("DISPLAY");
    }

private:
    pid_t xvfb_ = 0;
};

const auto* const kDisplay = ::testing::AddGlobalTestEnvironment(new XDisplay);

double meanAbsDifference(const ImageLayer& a, const ImageLayer& b) {
    double sum = 0.0;
    for (std::size_t i = 0; i < a.data.size(); ++i) sum += std::abs(double(a.data[i]) - double(b.data[i]));
    return sum / double(a.data.size());
}

double mean(const ImageLayer& a) {
    double sum = 0.0;
    for (float v : a.data) sum += v;
    return sum / double(a.data.size());
}

TEST(ViewerCli, WithoutADisplayExitsNonZeroAndSuggestsRender) {
    std::string saved = std::getenv("DISPLAY") ? std::getenv("DISPLAY") : "";
    unsetenv("DISPLAY");
    std::string savedWayland = std::getenv("WAYLAND_DISPLAY") ? std::getenv("WAYLAND_DISPLAY") : "";
    unsetenv("WAYLAND_DISPLAY");
    auto r = runVoxgi("view cornell-box");
    if (!saved.empty()) setenv("DISPLAY", saved.c_str(), 1);
    if (!savedWayland.empty()) setenv("WAYLAND_DISPLAY", savedWayland.c_str(), 1);
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.output.find("no display"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("voxgi render"), std::string::npos) << r.output;
    // One line: the message and nothing else.
    EXPECT_EQ(r.output.find('\n'), r.output.size() - 1) << r.output;
}

TEST(ViewerCli, BadOptionsAreOneLineErrors) {
    auto r = runVoxgi("view cornell-box --window 12");
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("--window 12"), std::string::npos) << r.output;
    r = runVoxgi("view cornell-box --method nosuch");
    EXPECT_EQ(r.exitCode, 2) << r.output;
    // A setting the method refuses: refused at start like `voxgi render` does, no window loop.
    r = runVoxgi("view cornell-box --method ddgi --set ddgi.rays=-5 --frames 1");
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("ddgi.rays"), std::string::npos) << r.output;
}

// The screenshot after N frames is the frame renderer's average: the same as `voxgi render`.
TEST(ViewerWindow, ScreenshotMatchesRenderOfTheSameView) {
    std::string dir = test::makeTempDir("view-shot");
    const std::string size = " --width 96 --height 96 --frames 4";
    for (const char* method : {"direct", "clpv"}) {
        std::string m = method;
        auto v = runVoxgi("view cornell-box --method " + m + size + " --screenshot " + dir + "/" + m + "-view.png");
        ASSERT_EQ(v.exitCode, 0) << v.output;
        ASSERT_TRUE(test::fileExists(dir + "/" + m + "-view.png"));
        auto r = runVoxgi("render cornell-box --method " + m + size + " -o " + dir + "/" + m + "-render.exr");
        ASSERT_EQ(r.exitCode, 0) << r.output;
        Image shot = readExr(dir + "/" + m + "-view.exr");
        Image ref = readExr(dir + "/" + m + "-render.exr");
        ASSERT_EQ(shot.width(), 96);
        ASSERT_EQ(shot.height(), 96);
        for (const char* layer : {"beauty", "direct", "indirect", "albedo", "normal"})
            ASSERT_NE(shot.find(layer), nullptr) << layer;
        const ImageLayer& s = *shot.find("beauty");
        const ImageLayer& f = *ref.find("beauty");
        double level = mean(f);
        EXPECT_GT(mean(s), 0.01) << "blank screenshot";
        // Different window systems (GLX vs EGL) on the same rasterizer: equal up to rounding.
        EXPECT_LT(meanAbsDifference(s, f), 1e-3 * level) << m;
        if (m == "clpv") {
            EXPECT_GT(mean(*shot.find("indirect")), 1e-3 * level) << "no indirect light";
        }
    }
}

// A camera path that starts elsewhere and arrives at the scene camera on frame 2: the camera
// moves restart the average, so the last 4 frames equal a 4-frame render of the scene view.
// Without the restart the first views would blend in and the difference would be large.
TEST(ViewerWindow, ScriptedCameraMovesRestartTheAccumulation) {
    std::string dir = test::makeTempDir("view-script-run");
    Scene scene = test::cornellBox();
    auto vec = [](glm::vec3 v) {
        return "[" + std::to_string(v.x) + "," + std::to_string(v.y) + "," + std::to_string(v.z) + "]";
    };
    glm::vec3 aside = scene.camera.eye + glm::vec3(0.15f, 0.05f, 0.0f);
    test::writeFile(dir + "/path.json", "{\"keys\": [{\"frame\": 0, \"eye\": " + vec(aside) + ", \"target\": " +
                                            vec(scene.camera.target) + "}, {\"frame\": 2, \"eye\": " +
                                            vec(scene.camera.eye) + ", \"target\": " + vec(scene.camera.target) + "}]}");
    const std::string common = "cornell-box --method direct --width 96 --height 96";
    auto v = runVoxgi("view " + common + " --frames 6 --script " + dir + "/path.json --screenshot " + dir + "/v.png");
    ASSERT_EQ(v.exitCode, 0) << v.output;
    auto r = runVoxgi("render " + common + " --frames 4 -o " + dir + "/r.exr");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    Image shot = readExr(dir + "/v.exr");
    Image ref = readExr(dir + "/r.exr");
    double level = mean(*ref.find("beauty"));
    EXPECT_LT(meanAbsDifference(*shot.find("beauty"), *ref.find("beauty")), 1e-3 * level);

    // Control: holding the side view for the first frames really changes the picture.
    auto aside2 = runVoxgi("view " + common + " --frames 1 --script " + dir + "/path.json --screenshot " + dir + "/a.png");
    ASSERT_EQ(aside2.exitCode, 0) << aside2.output;
    Image side = readExr(dir + "/a.exr");
    EXPECT_GT(meanAbsDifference(*side.find("beauty"), *ref.find("beauty")), 0.05 * level);
}

// Switching the method live (a script event, as the M key or the panel does) restarts the
// average with a fresh technique: 4 frames after the switch equal a 4-frame `voxgi render` with
// that method. A dump event writes the technique's .vdb, a reload event rebuilds the shaders,
// and the probe and voxel views draw without disturbing the screenshot.
TEST(ViewerWindow, LiveMethodSwitchDumpAndReload) {
    std::string dir = test::makeTempDir("view-switch");
    test::writeFile(dir + "/events.json",
                    "{\"events\": [{\"frame\": 0, \"show\": \"voxels_blocker\"}, {\"frame\": 1, \"action\": \"reload\"},"
                    " {\"frame\": 2, \"method\": \"clpv\"}, {\"frame\": 4, \"action\": \"dump\"},"
                    " {\"frame\": 4, \"show\": \"probes\"}, {\"frame\": 4, \"show\": \"indirect\"}]}");
    const std::string common = "cornell-box --width 96 --height 96";
    auto v = runVoxgi("view " + common + " --method direct --frames 6 --script " + dir + "/events.json --out-dir " + dir +
                      " --screenshot " + dir + "/v.png");
    ASSERT_EQ(v.exitCode, 0) << v.output;
    EXPECT_NE(v.output.find("shaders reloaded"), std::string::npos) << v.output;
    ASSERT_TRUE(test::fileExists(dir + "/voxgi-view-000-clpv.vdb")) << v.output;
    EXPECT_GT(std::filesystem::file_size(dir + "/voxgi-view-000-clpv.vdb"), 1000u);
    auto r = runVoxgi("render " + common + " --method clpv --frames 4 -o " + dir + "/r.exr");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    Image shot = readExr(dir + "/v.exr");
    Image ref = readExr(dir + "/r.exr");
    double level = mean(*ref.find("beauty"));
    EXPECT_GT(mean(*shot.find("indirect")), 1e-3 * level) << "the switch to clpv brought no indirect light";
    EXPECT_LT(meanAbsDifference(*shot.find("beauty"), *ref.find("beauty")), 1e-3 * level);

    test::writeFile(dir + "/bad.json", "{\"events\": [{\"frame\": 0, \"action\": \"explode\"}]}");
    auto bad = runVoxgi("view " + common + " --frames 1 --script " + dir + "/bad.json");
    EXPECT_EQ(bad.exitCode, 2) << bad.output;
    EXPECT_NE(bad.output.find("unknown action 'explode'"), std::string::npos) << bad.output;
}

// Animated lights reach both the direct light and the GI method. The animation restarts the
// average every frame, so the moving run's picture is one frame with the first frame's sample
// pattern (no jitter, the first area-light sample): exactly what a 1-frame still run renders,
// except for where the light is. Both layers must differ by more than a few percent.
TEST(ViewerWindow, AnimatedLightsMoveDirectAndIndirectLight) {
    std::string dir = test::makeTempDir("view-animate");
    test::writeFile(dir + "/animate.json", "{\"events\": [{\"frame\": 0, \"action\": \"animate_lights\"}]}");
    const std::string common = "view cornell-box --method lpv --width 96 --height 96 --no-panel";
    auto moving = runVoxgi(common + " --frames 8 --script " + dir + "/animate.json --screenshot " + dir + "/moving.png");
    ASSERT_EQ(moving.exitCode, 0) << moving.output;
    auto still = runVoxgi(common + " --frames 1 --screenshot " + dir + "/still.png");
    ASSERT_EQ(still.exitCode, 0) << still.output;
    auto again = runVoxgi(common + " --frames 1 --screenshot " + dir + "/again.png");
    ASSERT_EQ(again.exitCode, 0) << again.output;
    Image a = readExr(dir + "/moving.exr");
    Image b = readExr(dir + "/still.exr");
    Image c = readExr(dir + "/again.exr");
    double direct = mean(*b.find("direct")), indirect = mean(*b.find("indirect"));
    ASSERT_GT(indirect, 0.0);
    // Control: two still runs agree, so any difference below is the light's motion.
    EXPECT_LT(meanAbsDifference(*c.find("beauty"), *b.find("beauty")), 1e-4 * direct);
    // 8/30 of a turn on a circle of radius 15% of the scene radius.
    EXPECT_GT(meanAbsDifference(*a.find("direct"), *b.find("direct")), 0.02 * direct);
    EXPECT_GT(meanAbsDifference(*a.find("indirect"), *b.find("indirect")), 0.02 * indirect);
}

// What the window shows (no panel, window = render size) is the screenshot PNG: same ACES +
// sRGB tone curve on the GPU as scenes/image.cpp on the CPU, within 8-bit rounding.
TEST(ViewerWindow, OnScreenPictureIsTheToneMappedScreenshot) {
    std::string dir = test::makeTempDir("view-window");
    auto v = runVoxgi("view cornell-box --method direct --width 96 --height 96 --window 96x96 --frames 2 --no-panel "
                      "--exposure 1 --screenshot " + dir + "/shot.png --capture-window " + dir + "/window.png");
    ASSERT_EQ(v.exitCode, 0) << v.output;
    int w1, h1, n1, w2, h2, n2;
    unsigned char* a = stbi_load((dir + "/shot.png").c_str(), &w1, &h1, &n1, 3);
    unsigned char* b = stbi_load((dir + "/window.png").c_str(), &w2, &h2, &n2, 3);
    ASSERT_TRUE(a && b);
    ASSERT_EQ(w1, w2);
    ASSERT_EQ(h1, h2);
    int worst = 0;
    double sum = 0.0;
    for (int i = 0; i < w1 * h1 * 3; ++i) {
        worst = std::max(worst, std::abs(int(a[i]) - int(b[i])));
        sum += a[i];
    }
    stbi_image_free(a);
    stbi_image_free(b);
    EXPECT_GT(sum / double(w1 * h1 * 3), 10.0) << "blank window";
    EXPECT_LE(worst, 2);
}

}  // namespace
}  // namespace voxgi
