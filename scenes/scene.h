// The scene model every part of voxgi reads: geometry in world space (metres), materials,
// lights in physical units, the camera, the sky and the GI settings block.
#pragma once

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scenes/gi_settings.h"
#include "scenes/large_pages.h"

namespace voxgi {

struct Camera {
    glm::vec3 eye{0.0f, 0.0f, 1.0f};
    glm::vec3 target{0.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float fovYDegrees = 45.0f;  // vertical field of view
    int width = 512;
    int height = 512;
    float nearPlane = 0.01f;
    float farPlane = 100.0f;

    glm::mat4 view() const;
    glm::mat4 projection() const;  // OpenGL clip space, depth in [-1, 1]
    float aspect() const { return float(width) / float(height); }
};

// The values of the kinds in shaders/shared/light_model.h (static_assert in scenes/light_model.cpp).
enum class LightType { Point, Spot, Directional, Quad };

// The light model (how each type reaches a point, and the unit of its emission) is
// shaders/shared/light_model.h; evaluators read lights through shading::packLight.
struct Light {
    LightType type = LightType::Point;
    std::string name;
    glm::vec3 position{0.0f};   // point, spot; quad: one corner
    glm::vec3 direction{0.0f, -1.0f, 0.0f};  // spot, directional: the way light travels
    glm::vec3 emission{1.0f};   // intensity (W/sr), irradiance (W/m^2) or radiance (W/(m^2 sr)), per the type
    float innerConeDegrees = 20.0f;  // spot: full intensity inside this half-angle
    float outerConeDegrees = 30.0f;  // spot: zero outside this half-angle
    float angularDiameterDegrees = 0.0f;  // directional: the disc the light comes from; 0 = one direction
    glm::vec3 edgeU{0.0f};      // quad: corner + s*edgeU + t*edgeV, s,t in [0,1]
    glm::vec3 edgeV{0.0f};

    // Quad helpers; the emitting side is cross(edgeU, edgeV).
    float area() const { return glm::length(glm::cross(edgeU, edgeV)); }
    glm::vec3 quadNormal() const { return glm::normalize(glm::cross(edgeU, edgeV)); }
    glm::vec3 quadCenter() const { return position + 0.5f * (edgeU + edgeV); }
};
// Every field alike: methods that keep their light between frames compare the lights with it.
bool operator==(const Light& a, const Light& b);
inline bool operator!=(const Light& a, const Light& b) { return !(a == b); }

// What rays that leave the scene see: radiance in W/(m^2 sr) by direction. A constant sky is
// `radiance` alone; atmosphere and environment-map skies are an equirectangular table
// (shaders/shared/sky.h; filled by scenes/sky_model.h), whose mean over the sphere `radiance`
// then holds.
enum class SkyType { Constant, Atmosphere, Envmap };

// A clear-sky atmosphere (scenes/sky_model.h makes its table and its sun).
struct AtmosphereDesc {
    glm::vec3 sunDirection{0.0f, -1.0f, 0.0f};  // unit, the way sunlight travels (downward)
    float turbidity = 3.0f;
    float groundAlbedo = 0.3f;   // the ground below the horizon, lit by the sun and the sky
    float sunIrradiance = 10.0f; // W/m^2 on a surface facing the sun above the atmosphere
    int width = 512;             // table columns (rows: half as many)
};

struct Sky {
    bool enabled = false;
    SkyType type = SkyType::Constant;
    glm::vec3 radiance{0.0f};
    int width = 0, height = 0;      // the table's size; 0 for a constant sky
    std::vector<glm::vec3> table;   // width * height texels, row 0 at the zenith
    // An atmosphere's own description, so its table can follow its sun (followSun).
    AtmosphereDesc atmosphere;
    // Counts the table's changes after loading (followSun): the frame uploads the table again
    // and rebuilds what was lit by the old one (the sky-lighting volume).
    int revision = 0;

    bool tabulated() const { return !table.empty(); }
    // The radiance arriving from unit direction `towardSky` (zero when disabled).
    glm::vec3 radianceAt(glm::vec3 towardSky) const;
};

// An 8-bit texture stored as sRGB-encoded RGBA, rows top first.
struct Texture {
    std::string path;
    int width = 0;
    int height = 0;
    LargeVector<std::uint8_t> rgba;  // read at random by rays: in large pages (large_pages.h)
    glm::vec3 averageLinear{0.0f};  // mean linear colour, for voxel albedo and sanity checks

    // Bilinear, repeat-wrapped lookup returning linear RGB; uv with v = 0 at the image bottom.
    glm::vec3 sampleLinear(glm::vec2 uv) const;
    // Starts loading the texels sampleLinear(uv) reads, for callers with other work to do first.
    void prefetch(glm::vec2 uv) const;
};

// The lookup behind Texture::sampleLinear, over any sRGB RGBA8 image (mip levels included).
glm::vec3 sampleSrgbBilinear(const std::uint8_t* rgba, int width, int height, glm::vec2 uv);
// sRGB 8-bit code to linear, and linear [0,1] to the nearest sRGB code.
float srgbToLinear(std::uint8_t code);
const float* srgbDecodeTable();  // the 256 values srgbToLinear returns, for inlined lookups
std::uint8_t linearToSrgb(float linear);

struct Material {
    std::string name;
    glm::vec3 albedo{0.8f};      // linear base colour (multiplied by the texture if any)
    glm::vec3 emission{0.0f};    // emitted radiance, W/(m^2 sr)
    float roughness = 1.0f;      // GGX perceptual roughness in [0, 1]
    float metallic = 0.0f;
    float specular = 0.0f;       // F0 of the dielectric GGX coat; 0 = pure Lambert
    float ior = 1.5f;
    float transmission = 0.0f;   // 1 = clear dielectric
    int albedoTexture = -1;      // index into Scene::textures

    bool isEmissive() const { return emission.x > 0.0f || emission.y > 0.0f || emission.z > 0.0f; }
};

// Triangles in world space. One material index per triangle.
struct Mesh {
    std::string name;
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;   // per vertex, may be empty (flat shading)
    std::vector<glm::vec2> uvs;       // per vertex, may be empty
    std::vector<std::uint32_t> indices;       // 3 per triangle
    std::vector<std::uint32_t> materialIds;   // 1 per triangle

    std::size_t triangleCount() const { return indices.size() / 3; }
    // The geometry Scene adds for a quad light (quadLightMeshName): the direct pass draws its
    // light, so ray tracers that gather indirect light must not count its emission again.
    bool isQuadLightGeometry() const { return name.rfind(kQuadLightMeshPrefix, 0) == 0; }
    static constexpr const char* kQuadLightMeshPrefix = "quad_light_";
};

struct Bounds {
    glm::vec3 min{1e30f};
    glm::vec3 max{-1e30f};
    // Non-finite points (NaN vertices, which renderers skip) are left out.
    void extend(glm::vec3 p) {
        if (!(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z))) return;
        min = glm::min(min, p);
        max = glm::max(max, p);
    }
    bool valid() const { return min.x <= max.x && min.y <= max.y && min.z <= max.z; }
    glm::vec3 center() const { return 0.5f * (min + max); }
    glm::vec3 extent() const { return max - min; }
};

// A named part of a scene for per-region error against the reference (docs/eval.md): the
// surface points inside `box` whose normal is within 45 degrees of `facing` (any normal when
// facing is zero).
struct Region {
    std::string name;
    Bounds box;
    glm::vec3 facing{0.0f};
};

struct Scene {
    std::string sourcePath;   // the file it was loaded from, or "" when built in code
    Camera camera;
    std::vector<Light> lights;
    Sky sky;
    std::vector<Material> materials;
    std::vector<Texture> textures;
    std::vector<Mesh> meshes;
    GiSettings gi;
    std::vector<Region> regions;

    Bounds bounds() const;
    std::size_t triangleCount() const;
    bool hasGlossyOrRefractive() const;

    // Appends the emitting geometry of every quad light as a one-sided mesh, so rasterizers
    // see the light and path tracers can hit it. Called by the loader; idempotent.
    void addQuadLightGeometry();
    // The name of the mesh addQuadLightGeometry gives quad light `light` (an index into lights).
    std::string quadLightMeshName(std::size_t light) const;
    // That mesh, or null before addQuadLightGeometry (or for a light of another type).
    const Mesh* quadLightMesh(std::size_t light) const;
};

}  // namespace voxgi
