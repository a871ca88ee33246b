#include "render/view/debug_overlay.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "volumes/geometry_volume.h"

namespace voxgi::view {

namespace {

struct CubeInstance {
    glm::vec4 centerHalf;
    glm::vec4 color;
};

struct LineVertex {
    glm::vec3 position;
    glm::vec3 color;
};

void addBox(std::vector<LineVertex>& lines, glm::vec3 lo, glm::vec3 hi, glm::vec3 color) {
    for (int axis = 0; axis < 3; ++axis)
        for (int corner = 0; corner < 4; ++corner) {
            glm::vec3 a = lo, b = hi;
            int u = (axis + 1) % 3, v = (axis + 2) % 3;
            a[u] = b[u] = (corner & 1) ? hi[u] : lo[u];
            a[v] = b[v] = (corner & 2) ? hi[v] : lo[v];
            a[axis] = lo[axis];
            b[axis] = hi[axis];
            lines.push_back({a, color});
            lines.push_back({b, color});
        }
}

void addCross(std::vector<LineVertex>& lines, glm::vec3 p, float size, glm::vec3 color) {
    for (int axis = 0; axis < 3; ++axis) {
        glm::vec3 d(0.0f);
        d[axis] = size;
        lines.push_back({p - d, color});
        lines.push_back({p + d, color});
    }
}

// Blocker strength: the largest fraction of light the voxel blocks over directions, from its
// linear SH (c0 Y00 + |c1| * 0.4886), clamped to [0, 1] like the LPV's use of it.
float blockerStrength(glm::vec4 sh) {
    float directional = glm::length(glm::vec3(sh.y, sh.z, sh.w));
    return std::clamp(0.282094792f * sh.x + 0.488602512f * directional, 0.0f, 1.0f);
}

glm::vec3 heat(float t) {
    return glm::clamp(glm::vec3(2.0f * t, 2.0f * t - 0.5f, 1.0f - 2.0f * t), glm::vec3(0.05f), glm::vec3(1.0f));
}

}  // namespace

// Largest rectangle of the render's aspect that fits the window, centred.
glm::ivec4 letterbox(int renderW, int renderH, int windowW, int windowH) {
    float scale = std::min(float(windowW) / float(renderW), float(windowH) / float(renderH));
    int w = std::max(1, int(std::lround(scale * float(renderW))));
    int h = std::max(1, int(std::lround(scale * float(renderH))));
    return {(windowW - w) / 2, (windowH - h) / 2, w, h};
}

struct DebugOverlay::Impl {
    gl::Program cubes = gl::Program::graphics("view/cubes.vert", "view/flat.frag");
    gl::Program lines = gl::Program::graphics("view/lines.vert", "view/flat.frag");
    gl::Program spheres = gl::Program::graphics("view/spheres.vert", "view/spheres.frag");
    gl::Handle sphereBuffer;
    std::size_t sphereCapacity = 0;
    gl::Handle emptyVao = gl::createVertexArray();
    gl::Handle lineVao = gl::createVertexArray();
    gl::Handle lineBuffer;
    std::size_t lineCapacity = 0;
    gl::Handle cubeBuffer;
    std::size_t cubeCount = 0;
    int builtResolution = 0;
    VoxelColor builtColor = VoxelColor::Albedo;

    void buildVoxels(const Scene& scene, const DebugViews& views) {
        Bounds b = scene.bounds();
        float longest = std::max({b.extent().x, b.extent().y, b.extent().z, 1e-6f});
        VoxelizeSettings settings;
        settings.voxelSize = longest / float(views.voxelResolution);
        SparseGeometryVolume volume = voxelizeScene(scene, settings);
        std::vector<CubeInstance> instances;
        float half = 0.5f * volume.voxelSize(0);
        for (const Brick& brick : volume.activeBricks(0))
            for (int z = 0; z < 8; ++z)
                for (int y = 0; y < 8; ++y)
                    for (int x = 0; x < 8; ++x) {
                        glm::ivec3 ijk = brick.origin + glm::ivec3(x, y, z);
                        if (!volume.occupied(ijk)) continue;
                        glm::vec3 color = views.voxelColor == VoxelColor::Albedo
                                              ? glm::pow(glm::clamp(volume.albedo(ijk), 0.0f, 1.0f), glm::vec3(1.0f / 2.2f))
                                              : heat(blockerStrength(volume.blockerSH(ijk)));
                        // Slightly smaller than the voxel so neighbouring cubes stay distinct.
                        instances.push_back({glm::vec4(volume.voxelCenter(ijk), 0.9f * half), glm::vec4(color, 1.0f)});
                    }
        cubeCount = instances.size();
        cubeBuffer = instances.empty() ? gl::Handle()
                                       : gl::createBuffer(instances.size() * sizeof(CubeInstance), instances.data(), 0);
        builtResolution = views.voxelResolution;
        builtColor = views.voxelColor;
    }

    void drawSpheres(const DebugDrawing& set, const glm::mat4& viewProjection, GLuint scenePosition, glm::ivec4 viewport,
                     glm::vec3 eye) {
        if (set.spheres.empty()) return;
        std::size_t bytes = set.spheres.size() * sizeof(DebugSphere);
        if (bytes > sphereCapacity) {
            sphereCapacity = 2 * bytes;
            sphereBuffer = gl::createBuffer(sphereCapacity);
        }
        glNamedBufferSubData(sphereBuffer.id(), 0, GLsizeiptr(bytes), set.spheres.data());
        spheres.use();
        spheres.set("uViewProjection", viewProjection);
        spheres.set("uShMode", set.shSpheres ? 1 : 0);
        spheres.set("uScale", set.shScale);
        spheres.set("uOccludeByScene", scenePosition != 0 ? 1 : 0);
        spheres.set("uViewport", glm::vec4(viewport));
        spheres.set("uEye", eye);
        spheres.set("uScenePosition", 0);
        if (scenePosition != 0) glBindTextureUnit(0, scenePosition);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, sphereBuffer.id());
        glBindVertexArray(emptyVao.id());
        glDrawArraysInstanced(GL_TRIANGLES, 0, 8 * 12 * 6, GLsizei(set.spheres.size()));
    }

    void drawLines(const std::vector<LineVertex>& vertices, const glm::mat4& viewProjection) {
        if (vertices.empty()) return;
        std::size_t bytes = vertices.size() * sizeof(LineVertex);
        if (bytes > lineCapacity) {
            lineCapacity = 2 * bytes;
            lineBuffer = gl::createBuffer(lineCapacity);
            glVertexArrayVertexBuffer(lineVao.id(), 0, lineBuffer.id(), 0, sizeof(LineVertex));
            glEnableVertexArrayAttrib(lineVao.id(), 0);
            glEnableVertexArrayAttrib(lineVao.id(), 1);
            glVertexArrayAttribFormat(lineVao.id(), 0, 3, GL_FLOAT, GL_FALSE, 0);
            glVertexArrayAttribFormat(lineVao.id(), 1, 3, GL_FLOAT, GL_FALSE, sizeof(glm::vec3));
            glVertexArrayAttribBinding(lineVao.id(), 0, 0);
            glVertexArrayAttribBinding(lineVao.id(), 1, 0);
        }
        glNamedBufferSubData(lineBuffer.id(), 0, GLsizeiptr(bytes), vertices.data());
        lines.use();
        lines.set("uViewProjection", viewProjection);
        glBindVertexArray(lineVao.id());
        glDrawArrays(GL_LINES, 0, GLsizei(vertices.size()));
    }
};

DebugOverlay::DebugOverlay() : impl_(std::make_unique<Impl>()) {}
DebugOverlay::~DebugOverlay() = default;

std::size_t DebugOverlay::draw(const Scene& scene, const DebugViews& views, glm::ivec4 viewport,
                               const std::vector<DebugDrawing>& drawings, GLuint scenePosition) {
    Bounds b = scene.bounds();
    bool anything = views.voxels || views.bounds || views.lights;
    for (const DebugDrawing& d : drawings) anything = anything || !d.spheres.empty() || !d.boxes.empty();
    if (!b.valid() || !anything) return 0;
    glViewport(viewport.x, viewport.y, viewport.z, viewport.w);
    glm::mat4 viewProjection = scene.camera.projection() * scene.camera.view();
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDisable(GL_BLEND);
    glClear(GL_DEPTH_BUFFER_BIT);
    std::size_t drawn = 0;
    if (views.voxels) {
        if (impl_->builtResolution != views.voxelResolution || impl_->builtColor != views.voxelColor)
            impl_->buildVoxels(scene, views);
        // The cubes replace the picture inside the viewport.
        glEnable(GL_SCISSOR_TEST);
        glScissor(viewport.x, viewport.y, viewport.z, viewport.w);
        glClearColor(0.1f, 0.1f, 0.12f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT);
        glDisable(GL_SCISSOR_TEST);
        if (impl_->cubeCount > 0) {
            impl_->cubes.use();
            impl_->cubes.set("uViewProjection", viewProjection);
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, impl_->cubeBuffer.id());
            glBindVertexArray(impl_->emptyVao.id());
            glDrawArraysInstanced(GL_TRIANGLES, 0, 36, GLsizei(impl_->cubeCount));
        }
        drawn = impl_->cubeCount;
    }
    bool occlude = views.occludeSpheres && !views.voxels;  // over voxels the picture is gone
    std::vector<LineVertex> lineVertices;
    for (const DebugDrawing& d : drawings) {
        impl_->drawSpheres(d, viewProjection, occlude ? scenePosition : 0, viewport, scene.camera.eye);
        drawn += d.spheres.size();
        for (const DebugBox& box : d.boxes) addBox(lineVertices, box.min, box.max, box.color);
    }
    float radius = 0.5f * glm::length(b.extent());
    if (views.bounds) addBox(lineVertices, b.min, b.max, glm::vec3(0.2f, 1.0f, 0.3f));
    if (views.lights)
        for (const Light& light : scene.lights) {
            glm::vec3 color(1.0f, 0.85f, 0.2f);
            if (light.type == LightType::Directional) {
                // The sun as a segment from outside the scene toward its centre.
                glm::vec3 c = b.center();
                lineVertices.push_back({c - 1.5f * radius * light.direction, color});
                lineVertices.push_back({c - 1.1f * radius * light.direction, color});
            } else {
                glm::vec3 p = light.type == LightType::Quad ? light.quadCenter() : light.position;
                addCross(lineVertices, p, 0.04f * radius, color);
                if (light.type == LightType::Spot) {
                    lineVertices.push_back({p, color});
                    lineVertices.push_back({p + 0.2f * radius * light.direction, color});
                }
            }
        }
    // Markers stay visible through geometry.
    glDisable(GL_DEPTH_TEST);
    impl_->drawLines(lineVertices, viewProjection);
    glViewport(0, 0, viewport.z + 2 * viewport.x, viewport.w + 2 * viewport.y);
    return drawn;
}

}  // namespace voxgi::view
