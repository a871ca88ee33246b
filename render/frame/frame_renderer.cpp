#include "render/frame/frame_renderer.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include <chrono>

#include "gi/methods.h"
#include "gi/raytrace/ray_tracer.h"
#include "gi/sky/sky_volume.h"
#include "gi/sky/sky_volume_texture.h"
#include "gi/sampling/sequences.h"
#include "render/frame/sun_cascades.h"
#include "scenes/errors.h"
#include "shaders/shared/sun_shadow.h"
#include "gl/scene_gpu.h"
#include "gl/context.h"
#include "gl/program.h"
#include "gl/resources.h"
#include "gl/screen_pass.h"

namespace voxgi {

namespace {

// View matrices of the six cube faces in GL's face order (+X, -X, +Y, -Y, +Z, -Z).
glm::mat4 cubeFaceView(int face, glm::vec3 eye) {
    static const glm::vec3 dirs[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    static const glm::vec3 ups[6] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
    return glm::lookAt(eye, eye + dirs[face], ups[face]);
}

glm::vec3 anyPerpendicular(glm::vec3 d) {
    return std::abs(d.y) < 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
}

}  // namespace

int defaultFrameCount(const Scene& scene) {
    for (const Light& l : scene.lights)
        if (l.type == LightType::Quad) return 64;
    return 1;
}

struct FrameRenderer::Impl {
    const Scene& scene;
    FrameOptions options;
    int width, height;  // the picture
    // The guard band the plan asks for, in pixels beyond each edge: the frame's targets are
    // larger by it, and resolve() crops the picture from their middle.
    int bandX = 0, bandY = 0;
    int targetWidth() const { return width + 2 * bandX; }
    int targetHeight() const { return height + 2 * bandY; }
    bool drawsBand() const { return bandX > 0 || bandY > 0; }
    int frames = 0;
    float sceneRadius;
    glm::vec3 sceneCenter;
    SceneGpu gpu;
    gl::StageTimers timers;
    FramePlan plan;
    std::unique_ptr<GiTechnique> technique;
    const bool hasSun;  // a directional light: cascaded maps (renderSunCascades)

    gl::Program gbufferProgram, shadowDepthProgram, shadowDistanceProgram, lightProgram, emissionProgram, skyLightProgram;
    // The sky-lighting volume, built the first time a plan has the sky_volume pass: Embree
    // traces it on the CPU, then its cells go to one 3D texture that the sky_light pass and the
    // techniques read.
    std::unique_ptr<RayTracer> skyTracer;
    std::unique_ptr<SkyVolume> skyVolume;
    std::unique_ptr<SkyVolumeTexture> skyTexture;
    // When the sky changes (Sky::revision): its table is uploaded again at once, and the volume
    // is traced again over frames (sky.update_ms a frame) while the old one still lights them.
    int skyRevision = 0;
    std::unique_ptr<SkyVolume> nextSkyVolume;
    gl::Handle gbufferFbo, gPosition, gNormal, gAlbedo, gEmission, gDepth;
    gl::Handle accumFbo, accum, indirectFbo, indirectAccum;
    gl::Handle shadowFbo, shadowDepth;
    // The sun's cascades: one depth layer each, read through two samplers (compare for PCF, raw
    // depths for the blocker search).
    gl::Handle sunFbo, sunDepth, sunCompareSampler, sunDepthSampler, sunTileDepth;
    gl::Program sunTileProgram;
    gl::Handle cubeFbo, cubeDistance, cubeDepth;
    gl::Handle emptyVao;

    Impl(const Scene& s, const FrameOptions& o, FramePlan p)
        : scene(s), options(o), width(o.width > 0 ? o.width : s.camera.width),
          height(o.height > 0 ? o.height : s.camera.height), gpu(s), plan(std::move(p)),
          technique(createTechnique(plan.method, s)),
          hasSun(std::any_of(s.lights.begin(), s.lights.end(), [](const Light& l) { return l.type == LightType::Directional; })) {
        skyRevision = s.sky.revision;  // the table SceneGpu uploaded
        Bounds b = s.bounds();
        sceneCenter = b.valid() ? b.center() : glm::vec3(0.0f);
        sceneRadius = b.valid() ? std::max(0.5f * glm::length(b.extent()), 1e-6f) : 1.0f;

        gbufferProgram = gl::Program::graphics("frame/gbuffer.vert", "frame/gbuffer.frag");
        shadowDepthProgram = gl::Program::graphics("frame/shadow.vert", "frame/shadow_depth.frag");
        shadowDistanceProgram = gl::Program::graphics("frame/shadow.vert", "frame/shadow_distance.frag");
        lightProgram = gl::Program::compute("frame/direct_light.comp");
        emissionProgram = gl::Program::compute("frame/emission.comp");
        skyLightProgram = gl::Program::compute("frame/sky_light.comp");
        emptyVao = gl::createVertexArray();

        if (options.sunCascades < 1 || options.sunCascades > shading::kMaxSunCascades)
            throw InputError("sun cascades: " + std::to_string(options.sunCascades) + " is outside [1, " +
                             std::to_string(shading::kMaxSunCascades) + "]");
        if (options.sunMapSize < shading::kSunTileTexels || options.sunMapSize % shading::kSunTileTexels != 0)
            throw InputError("sun map size: " + std::to_string(options.sunMapSize) + " is not a multiple of " +
                             std::to_string(shading::kSunTileTexels));

        shadowDepth = gl::createTexture(GL_TEXTURE_2D, GL_DEPTH_COMPONENT32F, options.shadowMapSize,
                                        options.shadowMapSize);
        glTextureParameteri(shadowDepth.id(), GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
        glTextureParameteri(shadowDepth.id(), GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
        shadowFbo = gl::createFramebuffer({}, shadowDepth.id(), "shadow map");

        if (hasSun) {
            sunTileProgram = gl::Program::compute("frame/sun_tile_depth.comp");
            sunFbo = gl::createFramebuffer();
            sunCompareSampler = gl::createSampler();
            sunDepthSampler = gl::createSampler();
            for (GLuint sampler : {sunCompareSampler.id(), sunDepthSampler.id()}) {
                glSamplerParameteri(sampler, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
                glSamplerParameteri(sampler, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
            }
            glSamplerParameteri(sunCompareSampler.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
            glSamplerParameteri(sunCompareSampler.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
            glSamplerParameteri(sunCompareSampler.id(), GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
            glSamplerParameteri(sunCompareSampler.id(), GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
            glSamplerParameteri(sunDepthSampler.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
            glSamplerParameteri(sunDepthSampler.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
            glSamplerParameteri(sunDepthSampler.id(), GL_TEXTURE_COMPARE_MODE, GL_NONE);
        }
        createTargets();

        cubeDistance = gl::createTexture(GL_TEXTURE_CUBE_MAP, GL_R32F, options.cubeShadowSize, options.cubeShadowSize);
        glTextureParameteri(cubeDistance.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(cubeDistance.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        cubeDepth = gl::createTexture(GL_TEXTURE_2D, GL_DEPTH_COMPONENT32F, options.cubeShadowSize,
                                      options.cubeShadowSize);
        cubeFbo = gl::createFramebuffer();
        glNamedFramebufferTexture(cubeFbo.id(), GL_DEPTH_ATTACHMENT, cubeDepth.id(), 0);
        glNamedFramebufferTextureLayer(cubeFbo.id(), GL_COLOR_ATTACHMENT0, cubeDistance.id(), 0, 0);
        gl::checkFramebuffer(cubeFbo.id(), "cube shadow map");
    }

    // The G-buffer and accumulation targets, at the picture's size plus the plan's guard band;
    // made again when a new method's band differs.
    void createTargets() {
        const float band = options.guardBand ? plan.technique.guardBand : 0.0f;
        bandX = int(std::lround(double(band) * width));
        bandY = int(std::lround(double(band) * height));
        const int w = targetWidth(), h = targetHeight();
        gPosition = gl::createTexture(GL_TEXTURE_2D, GL_RGBA32F, w, h);
        gNormal = gl::createTexture(GL_TEXTURE_2D, GL_RGBA16F, w, h);
        gAlbedo = gl::createTexture(GL_TEXTURE_2D, GL_RGBA16F, w, h);
        gEmission = gl::createTexture(GL_TEXTURE_2D, GL_RGBA32F, w, h);
        gDepth = gl::createTexture(GL_TEXTURE_2D, GL_DEPTH_COMPONENT32F, w, h);
        gbufferFbo = gl::createFramebuffer({gPosition.id(), gNormal.id(), gAlbedo.id(), gEmission.id()}, gDepth.id(),
                                           "G-buffer");
        const float zero[4] = {0, 0, 0, 0};
        // Cleared once: a plan without the gbuffer pass (no triangles) sees the sky everywhere.
        for (int i = 0; i < 4; ++i) glClearNamedFramebufferfv(gbufferFbo.id(), GL_COLOR, i, zero);
        accum = gl::createTexture(GL_TEXTURE_2D, GL_RGBA32F, w, h);
        accumFbo = gl::createFramebuffer({accum.id()}, 0, "accumulation");
        indirectAccum = gl::createTexture(GL_TEXTURE_2D, GL_RGBA32F, w, h);
        indirectFbo = gl::createFramebuffer({indirectAccum.id()}, 0, "indirect accumulation");
        glClearNamedFramebufferfv(accumFbo.id(), GL_COLOR, 0, zero);
        glClearNamedFramebufferfv(indirectFbo.id(), GL_COLOR, 0, zero);
        if (hasSun) {
            // The picture's cascades, and one more over the band's surfaces (renderSunCascades).
            const int layers = options.sunCascades + (drawsBand() ? 1 : 0);
            const int tiles = options.sunMapSize / shading::kSunTileTexels;
            sunTileDepth = gl::createTexture(GL_TEXTURE_2D_ARRAY, GL_R32F, tiles, tiles, layers);
            glTextureParameteri(sunTileDepth.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
            glTextureParameteri(sunTileDepth.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
            sunDepth = gl::createTexture(GL_TEXTURE_2D_ARRAY, GL_DEPTH_COMPONENT32F, options.sunMapSize, options.sunMapSize,
                                         layers);
            sunMapsKey.clear();
        }
    }

    // The scene's camera over the picture.
    Camera pictureCamera() const {
        Camera cam = scene.camera;
        cam.width = width;
        cam.height = height;
        return cam;
    }

    // The scene's camera over the targets: the picture's pixels with the band's around them, at
    // the same angle per pixel (the vertical field widened by the band; the aspect follows).
    Camera targetCamera() const {
        Camera cam = pictureCamera();
        cam.width = targetWidth();
        cam.height = targetHeight();
        if (bandY > 0)
            cam.fovYDegrees = glm::degrees(2.0f * std::atan(std::tan(0.5f * glm::radians(cam.fovYDegrees)) *
                                                            float(cam.height) / float(height)));
        return cam;
    }

    glm::mat4 lastViewProjection{1.0f};
    bool viewProjectionSet = false;  // by a G-buffer pass; without one the sky pass makes its own

    GBufferView gbufferView() const {
        GBufferView v;
        v.position = gPosition.id();
        v.normal = gNormal.id();
        v.albedo = gAlbedo.id();
        v.emission = gEmission.id();
        v.width = targetWidth();
        v.height = targetHeight();
        v.fovYDegrees = targetCamera().fovYDegrees;
        v.pictureOrigin = {bandX, bandY};
        v.eye = scene.camera.eye;
        v.viewProjection = lastViewProjection;
        v.tracedRoughness = technique && plan.runs("hybrid.trace") ? technique->tracedRoughness() : -1.0f;
        return v;
    }

    glm::mat4 cameraViewProjection(glm::vec2 jitterPixels) const {
        const Camera cam = targetCamera();
        glm::mat4 proj = cam.projection();
        proj[2][0] += 2.0f * jitterPixels.x / float(cam.width);
        proj[2][1] += 2.0f * jitterPixels.y / float(cam.height);
        return proj * cam.view();
    }

    void renderGBuffer() {
        glm::vec2 jitter = (options.jitter && frames > 0) ? r2Sequence(frames, glm::vec2(0.5f)) - glm::vec2(0.5f) : glm::vec2(0.0f);
        timers.begin("gbuffer");
        glBindFramebuffer(GL_FRAMEBUFFER, gbufferFbo.id());
        glViewport(0, 0, targetWidth(), targetHeight());
        const float zero[4] = {0, 0, 0, 0};
        for (int i = 0; i < 4; ++i) glClearBufferfv(GL_COLOR, i, zero);
        glClear(GL_DEPTH_BUFFER_BIT);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glDisable(GL_CULL_FACE);
        glDisable(GL_BLEND);
        gbufferProgram.use();
        lastViewProjection = cameraViewProjection(jitter);
        viewProjectionSet = true;
        gbufferProgram.set("uViewProjection", lastViewProjection);
        gbufferProgram.set("uEye", scene.camera.eye);
        gbufferProgram.set("uTextures", 0);
        gpu.bind(0);
        gpu.draw();
        timers.end();
    }

    void renderCubeShadow(glm::vec3 eye) {
        timers.begin("shadow_cube");
        glBindFramebuffer(GL_FRAMEBUFFER, cubeFbo.id());
        glViewport(0, 0, options.cubeShadowSize, options.cubeShadowSize);
        glEnable(GL_DEPTH_TEST);
        glDisable(GL_BLEND);
        glDisable(GL_CULL_FACE);
        shadowDistanceProgram.use();
        shadowDistanceProgram.set("uLightPosition", eye);
        // Every length is relative to the scene so the same scene at any scale renders the same.
        float farPlane = glm::length(eye - sceneCenter) + 2.0f * sceneRadius;
        glm::mat4 proj = glm::perspective(glm::radians(90.0f), 1.0f, 1e-4f * sceneRadius, farPlane);
        const float far[4] = {1e30f, 0, 0, 0};
        for (int face = 0; face < 6; ++face) {
            glNamedFramebufferTextureLayer(cubeFbo.id(), GL_COLOR_ATTACHMENT0, cubeDistance.id(), 0, face);
            glClearBufferfv(GL_COLOR, 0, far);
            glClear(GL_DEPTH_BUFFER_BIT);
            shadowDistanceProgram.set("uViewProjection", proj * cubeFaceView(face, eye));
            gpu.draw();
        }
        timers.end();
    }

    // Depth-only drawing into `framebuffer` (size^2) with the slope-scaled offset shadow maps use.
    void beginDepthMapPass(GLuint framebuffer, int size) {
        glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
        glViewport(0, 0, size, size);
        glEnable(GL_DEPTH_TEST);
        glDisable(GL_BLEND);
        glDisable(GL_CULL_FACE);
        glEnable(GL_POLYGON_OFFSET_FILL);
        glPolygonOffset(1.5f, 2.0f);
        shadowDepthProgram.use();
    }

    glm::mat4 renderMapShadow(const glm::mat4& viewProjection) {
        timers.begin("shadow_map");
        beginDepthMapPass(shadowFbo.id(), options.shadowMapSize);
        glClear(GL_DEPTH_BUFFER_BIT);
        shadowDepthProgram.set("uViewProjection", viewProjection);
        gpu.draw();
        glDisable(GL_POLYGON_OFFSET_FILL);
        timers.end();
        glm::mat4 bias = glm::translate(glm::mat4(1.0f), glm::vec3(0.5f)) * glm::scale(glm::mat4(1.0f), glm::vec3(0.5f));
        return bias * viewProjection;
    }

    // What the sun's maps were last drawn for: the geometry does not move, so while the camera
    // and the sun stand still (frames that accumulate) the maps are kept (FrameOptions::keepSunMaps).
    std::vector<float> sunMapsKey;

    // The cascades of the sun travelling along `direction`, drawn into their layers.
    SunCascades renderSunCascades(glm::vec3 direction) {
        timers.begin("shadow_sun");
        // Fitted to the picture's view, so that its shadows are the same with a guard band as
        // without (cascades fitted to the wider view have coarser texels); one more, coarse, over
        // the whole targets' view shadows the band's surfaces that the picture's leave out (the
        // shader takes the first map that holds a point).
        SunCascades fit = fitSunCascades(pictureCamera(), direction, scene.bounds(), options.sunMapSize, options.sunCascades);
        if (drawsBand())
            fit.cascades.push_back(fitSunCascades(targetCamera(), direction, scene.bounds(), options.sunMapSize, 1).cascades[0]);
        std::vector<float> key = {direction.x, direction.y, direction.z};
        for (const SunCascade& c : fit.cascades) key.insert(key.end(), &c.worldToMap[0][0], &c.worldToMap[0][0] + 16);
        if (options.keepSunMaps && key == sunMapsKey) {
            timers.end();
            return fit;
        }
        sunMapsKey = std::move(key);
        beginDepthMapPass(sunFbo.id(), options.sunMapSize);
        for (std::size_t c = 0; c < fit.cascades.size(); ++c) {
            glNamedFramebufferTextureLayer(sunFbo.id(), GL_DEPTH_ATTACHMENT, sunDepth.id(), 0, GLint(c));
            glClear(GL_DEPTH_BUFFER_BIT);
            // The maps' xy are [0, 1]: undo the bias into clip space for drawing.
            const glm::mat4 unbias = glm::scale(glm::mat4(1.0f), glm::vec3(2.0f)) *
                                     glm::translate(glm::mat4(1.0f), glm::vec3(-0.5f));
            shadowDepthProgram.set("uViewProjection", unbias * fit.cascades[c].worldToMap);
            gpu.draw();
        }
        glDisable(GL_POLYGON_OFFSET_FILL);
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
        sunTileProgram.use();
        glBindTextureUnit(0, sunDepth.id());
        sunTileProgram.set("uSunDepth", 0);
        glBindImageTexture(0, sunTileDepth.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_R32F);
        const GLuint tiles = GLuint(options.sunMapSize / shading::kSunTileTexels);
        glDispatchCompute(tiles, tiles, GLuint(fit.cascades.size()));
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
        timers.end();
        return fit;
    }

    // A full-screen pass that adds into `framebuffer` (an accumulation target).
    void beginAdditivePass(GLuint framebuffer) {
        glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
        glViewport(0, 0, targetWidth(), targetHeight());
        glDisable(GL_DEPTH_TEST);
        glEnable(GL_BLEND);
        glBlendFunc(GL_ONE, GL_ONE);
    }

    // This frame's surfaces seen through mirrors and glass (the hybrid method), lit by the same
    // passes as the G-buffer into their own targets.
    std::vector<SecondaryLayerView> layers;

    // Draws go to the layer's light target, only where it holds surfaces (until GL_SCISSOR_TEST
    // is disabled again).
    void beginLayer(const SecondaryLayerView& layer) {
        glBindFramebuffer(GL_FRAMEBUFFER, layer.lightFramebuffer);
        glEnable(GL_SCISSOR_TEST);
        glScissor(layer.scissor.x, layer.scissor.y, layer.scissor.z, layer.scissor.w);
    }

    // The G-buffer's textures on units 0-3 (and, for a layer, its viewers on unit 9).
    void bindSurfaces(gl::Program& program, const GBufferView& g) { bindGBufferTextures(program, g); }

    void beginLightPass() {
        beginAdditivePass(accumFbo.id());
        bindSurfaces(lightProgram, gbufferView());
        glBindTextureUnit(4, cubeDistance.id());
        glBindTextureUnit(5, shadowDepth.id());
        glBindTextureUnit(6, sunDepth.id());
        glBindSampler(6, sunCompareSampler.id());
        glBindTextureUnit(7, sunDepth.id());
        glBindSampler(7, sunDepthSampler.id());
        glBindTextureUnit(8, sunTileDepth.id());
        const char* names[5] = {"uShadowCube", "uShadow2D", "uSunShadow", "uSunDepth", "uSunTileDepth"};
        for (int i = 0; i < 5; ++i) lightProgram.set(names[i], i + 4);
        lightProgram.set("uViewOrigin", 9);
        lightProgram.set("uViewOriginPerPixel", 0);
        lightProgram.set("uFrame", frames);
        lightProgram.set("uPictureOrigin", glm::ivec2(bandX, bandY));  // as GBufferView::pictureOrigin
        lightProgram.set("uEye", scene.camera.eye);
        gpu.bindLights();
    }

    // Light `index` of the scene (the shader reads it from the lights buffer) at quad point
    // `quadSample`, shadowed by the cube map around `shadowEye` or the 2D map `shadowMatrix`.
    void drawLight(std::size_t index, glm::vec2 quadSample, glm::vec3 shadowEye, const glm::mat4& shadowMatrix,
                   float shadowTexel) {
        timers.begin("direct_light");
        beginLightPass();
        lightProgram.set("uLight", int(index));
        lightProgram.set("uQuadSample", quadSample);
        lightProgram.set("uShadowEye", shadowEye);
        lightProgram.set("uShadowMatrix", shadowMatrix);
        lightProgram.set("uShadowTexel", shadowTexel);
        gl::addToBoundTarget(lightProgram);
        // The same light and shadow on the surfaces mirrors and glass show.
        for (const SecondaryLayerView& layer : layers) {
            beginLayer(layer);
            bindSurfaces(lightProgram, layer.surfaces);
            glBindTextureUnit(9, layer.surfaces.viewOrigin);
            lightProgram.set("uViewOriginPerPixel", 1);
            gl::addToBoundTarget(lightProgram);
        }
        glDisable(GL_SCISSOR_TEST);
        glBindSampler(6, 0);  // the units go back to their textures' own sampling
        glBindSampler(7, 0);
        timers.end();
    }

    void renderLight(const Light& light, std::size_t index) {
        const float cubeTexel = 2.0f / float(options.cubeShadowSize);
        switch (light.type) {
            case LightType::Point:
                renderCubeShadow(light.position);
                drawLight(index, glm::vec2(0.0f), light.position, glm::mat4(1.0f), cubeTexel);
                break;
            case LightType::Quad: {
                // One point of the quad per frame (the light model turns it into a point light);
                // the shadow cube sits just off the emitter so that it does not shadow itself.
                glm::vec2 uv = r2Sequence(frames, glm::vec2(0.5f) + 0.1f * float(index));
                glm::vec3 p = light.position + uv.x * light.edgeU + uv.y * light.edgeV +
                              light.quadNormal() * (1e-4f * sceneRadius);
                renderCubeShadow(p);
                drawLight(index, uv, p, glm::mat4(1.0f), cubeTexel);
                break;
            }
            case LightType::Spot: {
                float outer = glm::radians(light.outerConeDegrees);
                glm::mat4 view = glm::lookAt(light.position, light.position + light.direction,
                                             anyPerpendicular(light.direction));
                glm::mat4 proj = glm::perspective(2.0f * outer + 0.05f, 1.0f, 1e-3f * sceneRadius,
                                                  glm::length(light.position - sceneCenter) + 2.0f * sceneRadius);
                glm::mat4 shadow = renderMapShadow(proj * view);
                float texel = 2.0f * std::tan(outer + 0.025f) / float(options.shadowMapSize);
                drawLight(index, glm::vec2(0.0f), glm::vec3(0.0f), shadow, texel);
                break;
            }
            case LightType::Directional: {
                const SunCascades fit = renderSunCascades(light.direction);
                lightProgram.set("uCascadeCount", int(fit.cascades.size()));
                for (std::size_t c = 0; c < fit.cascades.size(); ++c) {
                    const std::string at = "[" + std::to_string(c) + "]";
                    lightProgram.set(("uCascadeMatrix" + at).c_str(), fit.cascades[c].worldToMap);
                    lightProgram.set(("uCascadeTexel" + at).c_str(), fit.cascades[c].texelWorld);
                }
                lightProgram.set("uWorldToLight", fit.worldToLight);
                lightProgram.set("uDepthRange", fit.depthRange);
                lightProgram.set("uSunTan", std::tan(0.5f * glm::radians(light.angularDiameterDegrees)));
                drawLight(index, glm::vec2(0.0f), glm::vec3(0.0f), glm::mat4(1.0f), 0.0f);
                break;
            }
        }
    }

    void renderEmission() {
        timers.begin("emission_sky");
        beginAdditivePass(accumFbo.id());
        emissionProgram.use();
        glBindTextureUnit(0, gPosition.id());
        glBindTextureUnit(3, gEmission.id());
        emissionProgram.set("uPosition", 0);
        emissionProgram.set("uEmission", 3);
        glBindTextureUnit(4, gpu.skyTexture());
        emissionProgram.set("uSkyTable", 4);
        const glm::mat4 viewProjection = viewProjectionSet ? lastViewProjection : cameraViewProjection(glm::vec2(0.0f));
        emissionProgram.set("uInverseViewProjection", glm::inverse(viewProjection));
        emissionProgram.set("uEye", scene.camera.eye);
        emissionProgram.set("uViewport", glm::vec2(float(targetWidth()), float(targetHeight())));
        gl::addToBoundTarget(emissionProgram);
        timers.end();
    }

    void buildSkyVolume() {
        const auto t0 = std::chrono::steady_clock::now();
        skyTracer = std::make_unique<RayTracer>(scene);
        skyVolume = std::make_unique<SkyVolume>(*skyTracer, readSkyVolumeDesc(scene.gi));
        skyVolume->update();  // the first build is whole: no frame is drawn without the sky's light
        skyTexture = std::make_unique<SkyVolumeTexture>(*skyVolume);
        timers.addCpu("sky_volume", std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    }

    // The sky changed since the last frame (followSun): a new table now, a new volume over frames.
    void followSky() {
        if (scene.sky.revision == skyRevision) return;
        skyRevision = scene.sky.revision;
        gpu.updateSky(scene.sky);
        if (skyVolume) nextSkyVolume = skyVolume->sameBricks();
    }

    void traceNextSkyVolume() {
        const auto t0 = std::chrono::steady_clock::now();
        const bool done = nextSkyVolume->update(nextSkyVolume->desc().updateMs);
        timers.addCpu("sky_volume", std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
        if (!done) return;
        // The texture refers to its volume: the old pair goes together.
        skyTexture = std::make_unique<SkyVolumeTexture>(*nextSkyVolume);
        skyVolume = std::move(nextSkyVolume);
        // The frames so far were lit by the old volume.
        clearAccumulation();
    }

    void clearAccumulation() {
        const float zero[4] = {0, 0, 0, 0};
        glClearNamedFramebufferfv(accumFbo.id(), GL_COLOR, 0, zero);
        glClearNamedFramebufferfv(indirectFbo.id(), GL_COLOR, 0, zero);
        frames = 0;
    }

    void renderSkyLight() {
        timers.begin("sky_light");
        beginAdditivePass(accumFbo.id());
        bindSurfaces(skyLightProgram, gbufferView());
        skyTexture->bind(skyLightProgram, 4);
        gl::addToBoundTarget(skyLightProgram);
        for (const SecondaryLayerView& layer : layers) {
            beginLayer(layer);
            bindSurfaces(skyLightProgram, layer.surfaces);
            gl::addToBoundTarget(skyLightProgram);
        }
        glDisable(GL_SCISSOR_TEST);
        timers.end();
    }

    void renderFrame() {
        gpu.updateLights(scene.lights);
        followSky();
        if (plan.runs("gbuffer")) renderGBuffer();
        if (plan.runs("sky_volume") && !skyTexture) buildSkyVolume();
        if (nextSkyVolume) traceNextSkyVolume();
        FrameInput input{scene, gpu, frames, timers, plan.technique, skyTexture.get()};
        GBufferView view = gbufferView();
        if (technique) technique->update(input, view);
        layers = technique ? technique->secondaryLayers() : std::vector<SecondaryLayerView>{};
        if (plan.runs("direct_light"))
            for (std::size_t i = 0; i < scene.lights.size(); ++i) renderLight(scene.lights[i], i);
        if (plan.runs("sky_light")) renderSkyLight();
        if (plan.runs("emission_sky")) renderEmission();
        if (technique) {
            view.directSum = accum.id();
            view.directFrames = frames + 1;
            beginAdditivePass(indirectFbo.id());
            glBindVertexArray(emptyVao.id());
            technique->applyIndirect(input, view);
            for (const SecondaryLayerView& layer : layers) {
                beginAdditivePass(layer.lightFramebuffer);
                beginLayer(layer);
                glBindVertexArray(emptyVao.id());
                technique->applyIndirect(input, layer.surfaces);
            }
            glDisable(GL_SCISSOR_TEST);
            beginAdditivePass(indirectFbo.id());
            glBindVertexArray(emptyVao.id());
            technique->composite(input, accumFbo.id(), indirectFbo.id());
        }
        glDisable(GL_BLEND);
        ++frames;
        timers.collect();
    }

    Image resolve() {
        Image image(width, height);
        const int tw = targetWidth(), th = targetHeight();
        // The picture is the targets' middle; GL rows run bottom to top, images top row first.
        auto targetTexel = [&](int x, int y) {
            return std::size_t(th - 1 - (y + bandY)) * std::size_t(tw) + std::size_t(x + bandX);
        };
        auto copyFlipped = [&](const std::vector<float>& src, int srcChannels, ImageLayer& dst, float scale) {
            for (int y = 0; y < height; ++y)
                for (int x = 0; x < width; ++x)
                    for (int c = 0; c < dst.channels; ++c)
                        dst.data[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * std::size_t(dst.channels) +
                                 std::size_t(c)] = scale * src[targetTexel(x, y) * std::size_t(srcChannels) + std::size_t(c)];
        };
        float inv = frames > 0 ? 1.0f / float(frames) : 0.0f;
        image.layer("beauty");  // first, so tools that read only RGB get the full image
        copyFlipped(gl::readTexture(accum.id(), tw, th, 4), 4, image.layer("direct"), inv);
        copyFlipped(gl::readTexture(indirectAccum.id(), tw, th, 4), 4, image.layer("indirect"), inv);
        {
            // Layers are all created above: the references below stay valid.
            const ImageLayer& d = *image.find("direct");
            const ImageLayer& i = *image.find("indirect");
            ImageLayer& b = image.layer("beauty");
            for (std::size_t k = 0; k < b.data.size(); ++k) b.data[k] = d.data[k] + i.data[k];
        }
        copyFlipped(gl::readTexture(gAlbedo.id(), tw, th, 4), 4, image.layer("albedo"), 1.0f);
        copyFlipped(gl::readTexture(gNormal.id(), tw, th, 4), 4, image.layer("normal"), 1.0f);
        // Depth as distance from the eye along the ray (0 for background).
        std::vector<float> pos = gl::readTexture(gPosition.id(), tw, th, 4);
        ImageLayer& depth = image.layer("depth", 1);
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) {
                const float* p = &pos[targetTexel(x, y) * 4];
                depth.data[std::size_t(y) * std::size_t(width) + std::size_t(x)] =
                    p[3] > 0.0f ? glm::length(glm::vec3(p[0], p[1], p[2]) - scene.camera.eye) : 0.0f;
            }
        return image;
    }
};

FrameRenderer::FrameRenderer(const Scene& scene, const FrameOptions& options, FramePlan plan)
    : impl_(std::make_unique<Impl>(scene, options, std::move(plan))) {}
FrameRenderer::FrameRenderer(const Scene& scene, const FrameOptions& options, const std::string& method)
    : FrameRenderer(scene, options, planFrame(scene, method, 1)) {}
FrameRenderer::~FrameRenderer() = default;
void FrameRenderer::renderFrame() { impl_->renderFrame(); }
int FrameRenderer::framesAccumulated() const { return impl_->frames; }
int FrameRenderer::width() const { return impl_->width; }
int FrameRenderer::height() const { return impl_->height; }
Image FrameRenderer::resolve() { return impl_->resolve(); }
gl::StageTimers& FrameRenderer::timers() { return impl_->timers; }
GiTechnique* FrameRenderer::technique() { return impl_->technique.get(); }
void FrameRenderer::resetAccumulation() { impl_->clearAccumulation(); }
void FrameRenderer::setMethod(const std::string& method) {
    FramePlan plan = planFrame(impl_->scene, method, 1);
    std::unique_ptr<GiTechnique> technique = createTechnique(method, impl_->scene);
    const bool newBand = plan.technique.guardBand != impl_->plan.technique.guardBand;
    impl_->plan = std::move(plan);
    impl_->technique = std::move(technique);
    if (newBand) impl_->createTargets();
    resetAccumulation();
}
const FramePlan& FrameRenderer::plan() const { return impl_->plan; }
FrameRenderer::Textures FrameRenderer::textures() const {
    return {impl_->accum.id(),
            impl_->indirectAccum.id(),
            impl_->gAlbedo.id(),
            impl_->gNormal.id(),
            impl_->gPosition.id(),
            impl_->targetWidth(),
            impl_->targetHeight(),
            {impl_->bandX, impl_->bandY}};
}

}  // namespace voxgi
