#include "scenes/scene_loader.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "scenes/errors.h"
#include "scenes/mesh_import.h"
#include "scenes/primitives.h"
#include "scenes/sky_model.h"

namespace voxgi {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// Reads one JSON object strictly: every key must be known, every value of the right type, and
// every error names the file and the JSON pointer of the field.
class Reader {
public:
    Reader(const std::string& file, const json& value, std::string pointer)
        : file_(file), value_(value), pointer_(std::move(pointer)) {}

    [[noreturn]] void fail(const std::string& what) const {
        throw InputError(file_ + ": " + (pointer_.empty() ? "/" : pointer_) + ": " + what);
    }

    void requireObject(const std::set<std::string>& known) const {
        if (!value_.is_object()) fail("expected an object");
        for (const auto& item : value_.items())
            if (!known.count(item.key())) {
                std::string list;
                for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
                child(item.key()).fail("unknown field (expected one of: " + list + ")");
            }
    }

    bool has(const std::string& key) const { return value_.is_object() && value_.contains(key); }
    Reader child(const std::string& key) const {
        static const json null;
        return Reader(file_, has(key) ? value_.at(key) : null, pointer_ + "/" + key);
    }
    Reader at(std::size_t i) const { return Reader(file_, value_.at(i), pointer_ + "/" + std::to_string(i)); }
    const json& raw() const { return value_; }

    float number() const {
        if (!value_.is_number()) fail("expected a number");
        double v = value_.get<double>();
        if (!std::isfinite(v)) fail("expected a finite number");
        return float(v);
    }
    float number(const std::string& key, float fallback) const { return has(key) ? child(key).number() : fallback; }
    // An integer that fits in int: larger JSON integers are an error, not a wrapped value.
    int integerValue() const {
        if (!value_.is_number_integer()) fail("expected an integer");
        const double v = value_.get<double>();
        if (v < double(std::numeric_limits<int>::min()) || v > double(std::numeric_limits<int>::max()))
            fail("integer out of range");
        return int(value_.get<long long>());
    }
    int integer(const std::string& key, int fallback) const {
        if (!has(key)) return fallback;
        Reader r = child(key);
        return r.integerValue();
    }
    std::string string() const {
        if (!value_.is_string()) fail("expected a string");
        return value_.get<std::string>();
    }
    std::string string(const std::string& key, const std::string& fallback) const {
        return has(key) ? child(key).string() : fallback;
    }
    glm::vec3 vec3() const {
        if (!value_.is_array() || value_.size() != 3) fail("expected [x, y, z]");
        return {at(0).number(), at(1).number(), at(2).number()};
    }
    glm::vec3 vec3(const std::string& key, glm::vec3 fallback) const { return has(key) ? child(key).vec3() : fallback; }
    glm::vec3 requiredVec3(const std::string& key) const {
        if (!has(key)) fail("missing field '" + key + "'");
        return child(key).vec3();
    }
    // A colour: one number (grey) or [r, g, b]; negative values are refused.
    glm::vec3 color(const std::string& key, glm::vec3 fallback) const {
        if (!has(key)) return fallback;
        Reader r = child(key);
        glm::vec3 c = r.value_.is_number() ? glm::vec3(r.number()) : r.vec3();
        if (c.x < 0.0f || c.y < 0.0f || c.z < 0.0f) r.fail("colour values must not be negative");
        return c;
    }
    std::size_t size() const {
        if (!value_.is_array()) fail("expected an array");
        return value_.size();
    }
    const std::string& file() const { return file_; }

private:
    const std::string& file_;
    const json& value_;
    std::string pointer_;
};

glm::mat4 readTransform(const Reader& r) {
    if (r.raw().is_null()) return glm::mat4(1.0f);
    r.requireObject({"translate", "rotate", "scale", "matrix"});
    if (r.has("matrix")) {
        Reader m = r.child("matrix");
        if (m.size() != 16) m.fail("expected 16 numbers (row-major 4x4)");
        if (r.has("translate") || r.has("rotate") || r.has("scale"))
            m.fail("use either matrix or translate/rotate/scale");
        glm::mat4 out;
        for (int row = 0; row < 4; ++row)
            for (int col = 0; col < 4; ++col) out[col][row] = m.at(std::size_t(row * 4 + col)).number();
        return out;
    }
    glm::mat4 t(1.0f);
    t = glm::translate(t, r.vec3("translate", glm::vec3(0.0f)));
    // Rotation in degrees about X, then Y, then Z (applied to the object in that order).
    glm::vec3 rot = r.vec3("rotate", glm::vec3(0.0f));
    t = glm::rotate(t, glm::radians(rot.z), glm::vec3(0, 0, 1));
    t = glm::rotate(t, glm::radians(rot.y), glm::vec3(0, 1, 0));
    t = glm::rotate(t, glm::radians(rot.x), glm::vec3(1, 0, 0));
    glm::vec3 s(1.0f);
    if (r.has("scale")) {
        Reader sr = r.child("scale");
        s = sr.raw().is_number() ? glm::vec3(sr.number()) : sr.vec3();
        if (s.x == 0.0f || s.y == 0.0f || s.z == 0.0f) sr.fail("scale must not be zero");
    }
    return glm::scale(t, s);
}

void readCamera(const Reader& r, Camera& cam) {
    r.requireObject({"eye", "target", "up", "fov", "resolution", "near", "far"});
    cam.eye = r.requiredVec3("eye");
    cam.target = r.requiredVec3("target");
    cam.up = r.vec3("up", cam.up);
    cam.fovYDegrees = r.number("fov", cam.fovYDegrees);
    if (!(cam.fovYDegrees > 0.0f && cam.fovYDegrees < 180.0f)) r.child("fov").fail("must be in (0, 180) degrees");
    if (glm::length(cam.target - cam.eye) <= 0.0f) r.child("target").fail("must differ from eye");
    if (glm::length(glm::cross(cam.target - cam.eye, cam.up)) <= 0.0f) r.child("up").fail("must not be parallel to the view direction");
    if (r.has("resolution")) {
        Reader res = r.child("resolution");
        if (res.size() != 2 || !res.raw()[0].is_number_integer() || !res.raw()[1].is_number_integer())
            res.fail("expected [width, height] integers");
        cam.width = res.at(0).integerValue();
        cam.height = res.at(1).integerValue();
        if (cam.width < 1 || cam.height < 1 || cam.width > 16384 || cam.height > 16384)
            res.fail("width and height must be in 1..16384");
    }
    cam.nearPlane = r.number("near", cam.nearPlane);
    cam.farPlane = r.number("far", cam.farPlane);
    if (!(cam.nearPlane > 0.0f && cam.farPlane > cam.nearPlane)) r.child("far").fail("need 0 < near < far");
}

// The fields `r` gives, over what `m` has: a material of the scene file, or one a mesh file
// brought that the scene adjusts (a "file" mesh's "material_settings").
void readMaterialFields(const Reader& r, Material& m, const fs::path& dir, Scene& scene) {
    r.requireObject({"albedo", "emission", "roughness", "metallic", "specular", "ior", "transmission", "texture"});
    m.albedo = r.color("albedo", m.albedo);
    if (m.albedo.x > 1.0f || m.albedo.y > 1.0f || m.albedo.z > 1.0f) r.child("albedo").fail("albedo must be at most 1");
    m.emission = r.color("emission", m.emission);
    auto unit = [&](const std::string& key, float fallback) {
        float v = r.number(key, fallback);
        if (v < 0.0f || v > 1.0f) r.child(key).fail("must be in [0, 1]");
        return v;
    };
    m.roughness = unit("roughness", m.roughness);
    m.metallic = unit("metallic", m.metallic);
    m.specular = unit("specular", m.specular);
    m.transmission = unit("transmission", m.transmission);
    m.ior = r.number("ior", m.ior);
    if (m.ior < 1.0f) r.child("ior").fail("must be at least 1");
    if (r.has("texture")) {
        std::string tex = r.child("texture").string();
        try {
            scene.textures.push_back(loadTexture((dir / tex).string()));
        } catch (const InputError& e) {
            r.child("texture").fail(e.what());
        }
        m.albedoTexture = int(scene.textures.size() - 1);
    }
}

Material readMaterial(const Reader& r, const std::string& name, const fs::path& dir, Scene& scene) {
    Material m;
    m.name = name;
    readMaterialFields(r, m, dir, scene);
    return m;
}

// A number of `r` at `key` in [lo, hi], or the fallback when absent.
// A directional light's disc is at most this wide (degrees): every direction of the disc
// delivers the light's full irradiance (shaders/shared/light_model.h), which stays within 0.4 %
// of the disc's true cosine-weighted mean up to here.
constexpr float kMaxAngularDiameterDegrees = 10.0f;

float numberIn(const Reader& r, const std::string& key, float fallback, float lo, float hi, const std::string& range) {
    const float v = r.number(key, fallback);
    if (!(v >= lo && v <= hi)) r.child(key).fail("must be in " + range);
    return v;
}

void readSky(const Reader& sky, const fs::path& dir, Scene& scene) {
    const std::string type = sky.string("type", "constant");
    if (type == "constant") {
        sky.requireObject({"type", "radiance"});
        scene.sky.enabled = true;
        scene.sky.radiance = sky.color("radiance", glm::vec3(1.0f));
    } else if (type == "atmosphere") {
        sky.requireObject({"type", "sun_direction", "sun_position", "turbidity", "ground_albedo", "sun_irradiance",
                           "resolution", "sun_light"});
        AtmosphereDesc a;
        if (sky.has("sun_direction") == sky.has("sun_position"))
            sky.fail("give one of 'sun_direction' (the way sunlight travels) and 'sun_position' (latitude, day, hour)");
        std::string sunField = "sun_direction";
        if (sky.has("sun_direction")) {
            a.sunDirection = sky.child("sun_direction").vec3();
            if (glm::length(a.sunDirection) <= 0.0f) sky.child("sun_direction").fail("must not be zero");
            a.sunDirection = glm::normalize(a.sunDirection);
        } else {
            sunField = "sun_position";
            const Reader p = sky.child("sun_position");
            p.requireObject({"latitude", "day", "hour"});
            for (const char* key : {"latitude", "day", "hour"})
                if (!p.has(key)) p.fail(std::string("missing field '") + key + "'");
            a.sunDirection = solarDirection(numberIn(p, "latitude", 0.0f, -90.0f, 90.0f, "[-90, 90] degrees"),
                                            numberIn(p, "day", 1.0f, 1.0f, 366.0f, "[1, 366]"),
                                            numberIn(p, "hour", 12.0f, 0.0f, 24.0f, "[0, 24] (solar time)"));
        }
        if (!(a.sunDirection.y < 0.0f)) sky.child(sunField).fail("the sun is not above the horizon");
        a.turbidity = numberIn(sky, "turbidity", a.turbidity, kMinTurbidity, kMaxTurbidity, "[2, 10], the model's fitted range");
        a.groundAlbedo = numberIn(sky, "ground_albedo", a.groundAlbedo, 0.0f, 1.0f, "[0, 1]");
        a.sunIrradiance = sky.number("sun_irradiance", a.sunIrradiance);
        if (!(a.sunIrradiance >= 0.0f)) sky.child("sun_irradiance").fail("must not be negative");
        a.width = sky.integer("resolution", a.width);
        if (a.width < 16 || a.width > 8192 || a.width % 2 != 0) sky.child("resolution").fail("must be an even number in [16, 8192]");
        const AtmosphereSky atmosphere = makeAtmosphere(a);
        scene.sky = atmosphere.sky;
        if (sky.has("sun_light") && !sky.child("sun_light").raw().is_boolean()) sky.child("sun_light").fail("expected true or false");
        if (!sky.has("sun_light") || sky.child("sun_light").raw().get<bool>()) {
            // The sun as the scene's directional light: its irradiance is what the atmosphere lets through.
            Light sun;
            sun.type = LightType::Directional;
            sun.name = kAtmosphereSunName;
            sun.direction = a.sunDirection;
            sun.emission = atmosphere.sunIrradiance;
            sun.angularDiameterDegrees = kSunAngularDiameterDegrees;
            scene.lights.push_back(sun);
        }
    } else if (type == "envmap") {
        sky.requireObject({"type", "path", "scale"});
        if (!sky.has("path")) sky.fail("missing field 'path'");
        const float scale = sky.number("scale", 1.0f);
        if (!(scale >= 0.0f)) sky.child("scale").fail("must not be negative");
        const std::string file = (dir / sky.child("path").string()).string();
        try {
            scene.sky = loadEnvmap(file, scale);
        } catch (const InputError& e) {
            sky.child("path").fail(e.what());
        }
    } else {
        sky.child("type").fail("expected one of: constant, atmosphere, envmap");
    }
}

Light readLight(const Reader& r) {
    Light l;
    std::string type = r.child("type").raw().is_null() ? "" : r.child("type").string();
    l.name = r.string("name", "");
    if (type == "point") {
        r.requireObject({"type", "name", "position", "intensity"});
        l.type = LightType::Point;
        l.position = r.requiredVec3("position");
        l.emission = r.color("intensity", glm::vec3(1.0f));
    } else if (type == "spot") {
        r.requireObject({"type", "name", "position", "direction", "intensity", "inner_angle", "outer_angle"});
        l.type = LightType::Spot;
        l.position = r.requiredVec3("position");
        l.direction = r.requiredVec3("direction");
        l.emission = r.color("intensity", glm::vec3(1.0f));
        l.innerConeDegrees = r.number("inner_angle", l.innerConeDegrees);
        l.outerConeDegrees = r.number("outer_angle", l.outerConeDegrees);
        if (!(l.outerConeDegrees > 0.0f && l.outerConeDegrees < 90.0f)) r.child("outer_angle").fail("must be in (0, 90) degrees");
        if (!(l.innerConeDegrees >= 0.0f && l.innerConeDegrees <= l.outerConeDegrees))
            r.child("inner_angle").fail("must be in [0, outer_angle]");
    } else if (type == "directional") {
        r.requireObject({"type", "name", "direction", "irradiance", "angular_diameter"});
        l.type = LightType::Directional;
        l.direction = r.requiredVec3("direction");
        l.emission = r.color("irradiance", glm::vec3(1.0f));
        l.angularDiameterDegrees = numberIn(r, "angular_diameter", 0.0f, 0.0f, kMaxAngularDiameterDegrees,
                                            "[0, 10] degrees (the sun: 0.53)");
    } else if (type == "quad") {
        r.requireObject({"type", "name", "corner", "edge_u", "edge_v", "radiance"});
        l.type = LightType::Quad;
        l.position = r.requiredVec3("corner");
        l.edgeU = r.requiredVec3("edge_u");
        l.edgeV = r.requiredVec3("edge_v");
        l.emission = r.color("radiance", glm::vec3(1.0f));
        if (l.area() <= 0.0f) r.child("edge_v").fail("quad light has zero area");
    } else {
        r.child("type").fail("expected one of: point, spot, directional, quad");
    }
    if (l.type == LightType::Spot || l.type == LightType::Directional) {
        if (glm::length(l.direction) <= 0.0f) r.child("direction").fail("must not be zero");
        l.direction = glm::normalize(l.direction);
    }
    return l;
}

void readMesh(const Reader& r, const fs::path& dir, Scene& scene,
              const std::map<std::string, std::uint32_t>& materialIds) {
    std::string type = r.child("type").raw().is_null() ? "" : r.child("type").string();
    std::set<std::string> common = {"type", "name", "material", "transform"};
    auto known = [&](std::set<std::string> extra) {
        extra.insert(common.begin(), common.end());
        r.requireObject(extra);
    };
    int material = -1;
    if (r.has("material")) {
        std::string name = r.child("material").string();
        auto it = materialIds.find(name);
        if (it == materialIds.end()) r.child("material").fail("unknown material '" + name + "'");
        material = int(it->second);
    } else if (type != "file") {
        r.fail("missing field 'material'");
    }
    glm::mat4 transform = readTransform(r.child("transform"));
    std::string name = r.string("name", type);
    Mesh mesh;
    auto mat = std::uint32_t(material);
    if (type == "file") {
        known({"path", "material_settings"});
        std::string file = r.child("path").string();
        const std::size_t materialsBefore = scene.materials.size();
        try {
            importMeshFile((dir / file).string(), transform, scene, material);
        } catch (const InputError& e) {
            r.child("path").fail(e.what());
        }
        // {"NAME": {fields}}: the file's material NAME with those fields changed (a polished
        // floor, glass in the windows), every other field as the file has it.
        if (r.has("material_settings")) {
            Reader settings = r.child("material_settings");
            if (!settings.raw().is_object()) settings.fail("expected an object of material names");
            for (const auto& item : settings.raw().items()) {
                bool found = false;
                for (std::size_t i = materialsBefore; i < scene.materials.size(); ++i)
                    if (scene.materials[i].name == item.key()) {
                        readMaterialFields(settings.child(item.key()), scene.materials[i], dir, scene);
                        found = true;
                    }
                if (!found) settings.child(item.key()).fail("the mesh file has no material '" + item.key() + "'");
            }
        }
        return;
    } else if (type == "box") {
        known({"inward"});
        bool inward = r.has("inward") && r.child("inward").raw().is_boolean() && r.child("inward").raw().get<bool>();
        mesh = makeBox(transform, mat, inward);
    } else if (type == "sphere") {
        known({"segments", "inward"});
        int segments = r.integer("segments", 32);
        if (segments < 4 || segments > 4096) r.child("segments").fail("must be in 4..4096");
        bool inward = r.has("inward") && r.child("inward").raw().is_boolean() && r.child("inward").raw().get<bool>();
        mesh = makeSphere(transform, mat, segments, inward);
    } else if (type == "quad") {
        known({"corners"});
        Reader c = r.child("corners");
        if (c.size() != 4) c.fail("expected 4 corners");
        std::array<glm::vec3, 4> corners;
        for (std::size_t i = 0; i < 4; ++i)
            corners[i] = glm::vec3(transform * glm::vec4(c.at(i).vec3(), 1.0f));
        mesh = makeQuad(corners, mat);
    } else if (type == "polygons") {
        known({"vertices", "faces"});
        Reader vr = r.child("vertices");
        std::vector<glm::vec3> vertices;
        for (std::size_t i = 0; i < vr.size(); ++i)
            vertices.push_back(glm::vec3(transform * glm::vec4(vr.at(i).vec3(), 1.0f)));
        Reader fr = r.child("faces");
        std::vector<std::vector<std::uint32_t>> faces;
        for (std::size_t i = 0; i < fr.size(); ++i) {
            Reader face = fr.at(i);
            if (face.size() < 3) face.fail("a face needs at least 3 vertex indices");
            std::vector<std::uint32_t> idx;
            for (std::size_t k = 0; k < face.size(); ++k) {
                const json& v = face.raw()[k];
                if (!v.is_number_integer() || v.get<long long>() < 0 || v.get<long long>() >= (long long)vertices.size())
                    face.at(k).fail("vertex index out of range");
                idx.push_back(v.get<std::uint32_t>());
            }
            faces.push_back(std::move(idx));
        }
        mesh = makePolygons(vertices, faces, mat);
    } else {
        r.child("type").fail("expected one of: file, box, sphere, quad, polygons");
    }
    mesh.name = name;
    scene.meshes.push_back(std::move(mesh));
}

// The gi block: "method" plus one object per technique holding scalar settings.
void readGi(const Reader& r, GiSettings& gi) {
    if (!r.raw().is_object()) r.fail("expected an object");
    for (const auto& item : r.raw().items()) {
        Reader section = r.child(item.key());
        if (item.key() == "method") {
            gi.set("method", section.string());
            continue;
        }
        if (!item.value().is_object()) section.fail("expected an object of settings");
        for (const auto& kv : item.value().items()) {
            const json& v = kv.value();
            std::string text;
            if (v.is_string()) text = v.get<std::string>();
            else if (v.is_boolean()) text = v.get<bool>() ? "true" : "false";
            else if (v.is_number()) text = v.dump();
            else section.child(kv.key()).fail("expected a number, boolean or string");
            gi.set(item.key() + "." + kv.key(), text);
        }
    }
}

std::string lineAndColumn(const std::string& text, std::size_t byte) {
    std::size_t line = 1, col = 1;
    for (std::size_t i = 0; i < byte && i < text.size(); ++i) {
        if (text[i] == '\n') { ++line; col = 1; } else { ++col; }
    }
    return "line " + std::to_string(line) + ", column " + std::to_string(col);
}

Region readRegion(const Reader& r, const std::vector<Region>& earlier) {
    r.requireObject({"name", "min", "max", "facing"});
    Region region;
    region.name = r.string("name", "");
    if (region.name.empty()) r.child("name").fail("a region needs a name");
    for (const Region& e : earlier)
        if (e.name == region.name) r.child("name").fail("a region named '" + region.name + "' already exists");
    region.box.min = r.requiredVec3("min");
    region.box.max = r.requiredVec3("max");
    if (!region.box.valid()) r.child("max").fail("must not be below min on any axis");
    const glm::vec3 facing = r.vec3("facing", glm::vec3(0.0f));
    if (facing != glm::vec3(0.0f)) {
        if (!(glm::length(facing) > 1e-6f)) r.child("facing").fail("expected a direction, or [0, 0, 0] for any");
        region.facing = glm::normalize(facing);
    }
    return region;
}

}  // namespace

namespace {
json parseJsonText(const std::string& text, const std::string& path);

// `"extends": "base.json"`: the base scene (a file in the same folder, so relative mesh paths
// mean the same in both) with this file's top-level fields replacing the base's. Chains of
// bases end within 8 files.
json resolveExtends(json doc, const std::string& path, int depth, std::string& label) {
    if (!doc.is_object() || !doc.contains("extends")) return doc;
    const json& name = doc.at("extends");
    if (!name.is_string()) throw InputError(path + ": /extends: expected a file name");
    const fs::path base = fs::path(path).parent_path() / name.get<std::string>();
    if (fs::path(name.get<std::string>()).has_parent_path())
        throw InputError(path + ": /extends: the base scene must be in the same folder (a file name, no path)");
    if (depth >= 8) throw InputError(path + ": /extends: more than 8 scenes extend one another (a cycle?)");
    std::ifstream in(base, std::ios::binary);
    if (!in) throw InputError(path + ": /extends: cannot open " + base.string());
    std::stringstream buffer;
    buffer << in.rdbuf();
    json merged = resolveExtends(parseJsonText(buffer.str(), base.string()), base.string(), depth + 1, label);
    if (!merged.is_object()) throw InputError(base.string() + ": expected a scene object");
    for (auto it = doc.begin(); it != doc.end(); ++it)
        if (it.key() != "extends") merged[it.key()] = it.value();
    label += " (extending " + base.string() + ")";
    return merged;
}
}  // namespace

namespace {
json parseJsonText(const std::string& text, const std::string& path) {
    json doc;
    try {
        doc = json::parse(text);
    } catch (const json::parse_error& e) {
        std::string what = e.what();
        auto pos = what.find("parse error");
        throw InputError(path + ": " + lineAndColumn(text, e.byte > 0 ? e.byte - 1 : 0) +
                         ": malformed JSON (" + (pos == std::string::npos ? what : what.substr(pos)) + ")");
    } catch (const json::exception& e) {
        // A number beyond double's range (1e999): the library reports no position.
        std::string what = e.what();
        auto pos = what.find("] ");
        throw InputError(path + ": malformed JSON (" + (pos == std::string::npos ? what : what.substr(pos + 2)) + ")");
    }
    return doc;
}
}  // namespace

Scene parseSceneJson(const std::string& text, const std::string& path) {
    std::string label = path;
    json doc = resolveExtends(parseJsonText(text, path), path, 0, label);
    Reader root(label, doc, "");
    root.requireObject({"camera", "lights", "sky", "materials", "meshes", "gi", "regions", "description"});
    Scene scene;
    scene.sourcePath = path;
    fs::path dir = fs::path(path).parent_path();
    if (!root.has("camera")) root.fail("missing field 'camera'");
    readCamera(root.child("camera"), scene.camera);

    std::map<std::string, std::uint32_t> materialIds;
    if (root.has("materials")) {
        Reader mats = root.child("materials");
        if (!mats.raw().is_object()) mats.fail("expected an object of named materials");
        for (const auto& item : mats.raw().items()) {
            scene.materials.push_back(readMaterial(mats.child(item.key()), item.key(), dir, scene));
            materialIds[item.key()] = std::uint32_t(scene.materials.size() - 1);
        }
    }
    if (root.has("lights")) {
        Reader lights = root.child("lights");
        for (std::size_t i = 0; i < lights.size(); ++i) scene.lights.push_back(readLight(lights.at(i)));
    }
    if (root.has("sky")) readSky(root.child("sky"), dir, scene);
    if (root.has("meshes")) {
        Reader meshes = root.child("meshes");
        for (std::size_t i = 0; i < meshes.size(); ++i) readMesh(meshes.at(i), dir, scene, materialIds);
    }
    if (root.has("gi")) readGi(root.child("gi"), scene.gi);
    if (root.has("regions")) {
        Reader regions = root.child("regions");
        for (std::size_t i = 0; i < regions.size(); ++i) scene.regions.push_back(readRegion(regions.at(i), scene.regions));
    }
    scene.addQuadLightGeometry();
    return scene;
}

Scene loadSceneFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path + ": cannot open scene file");
    std::stringstream buffer;
    buffer << in.rdbuf();
    return parseSceneJson(buffer.str(), path);
}

Scene sceneFromMeshFile(const std::string& path) {
    Scene scene;
    scene.sourcePath = path;
    importMeshFile(path, glm::mat4(1.0f), scene);
    Bounds b = scene.bounds();
    float radius = 0.5f * glm::length(b.extent());
    scene.camera.target = b.center();
    scene.camera.eye = b.center() + glm::vec3(0.3f, 0.4f, 1.0f) * (2.2f * radius);
    scene.camera.nearPlane = 0.01f * radius;
    scene.camera.farPlane = 10.0f * radius;
    Light sun;
    sun.type = LightType::Directional;
    sun.name = "sun";
    sun.direction = glm::normalize(glm::vec3(-0.3f, -1.0f, -0.2f));
    sun.emission = glm::vec3(3.0f);
    sun.angularDiameterDegrees = kSunAngularDiameterDegrees;
    scene.lights.push_back(sun);
    scene.sky.enabled = true;
    scene.sky.radiance = glm::vec3(0.2f, 0.25f, 0.35f);
    return scene;
}

Scene loadSceneOrMesh(const std::string& path) {
    if (fs::path(path).extension() == ".json") return loadSceneFile(path);
    return sceneFromMeshFile(path);
}

std::string builtinScenePath(const std::string& name) {
    const char* env = std::getenv("VOXGI_SCENE_DIR");
    fs::path dir = env && *env ? fs::path(env) : fs::path(VOXGI_SCENE_DIR);
    return (dir / (name + ".json")).string();
}

void requireRenderable(const Scene& scene, const std::string& source) {
    auto finite = [](glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
    std::size_t usable = 0;
    float largest = 0.0f;
    for (const Mesh& mesh : scene.meshes) {
        for (const glm::vec3& p : mesh.positions)
            if (finite(p)) largest = std::max(largest, std::max(std::abs(p.x), std::max(std::abs(p.y), std::abs(p.z))));
        for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
            const glm::vec3 a = mesh.positions[mesh.indices[3 * t]], b = mesh.positions[mesh.indices[3 * t + 1]],
                            c = mesh.positions[mesh.indices[3 * t + 2]];
            const float area = glm::length(glm::cross(b - a, c - a));
            usable += finite(a) && finite(b) && finite(c) && std::isfinite(area) && area > 0.0f;
        }
    }
    if (largest > kMaxCoordinate) {
        char value[32];
        std::snprintf(value, sizeof value, "%.3g", double(largest));
        throw InputError(source + ": meshes: coordinates reach " + value + " m; voxgi accepts up to 1e12 m from the origin");
    }
    if (usable == 0) throw InputError(source + ": meshes: no triangle with finite vertices and non-zero area");
    const Camera& c = scene.camera;
    const glm::vec3 forward = c.target - c.eye;
    if (!finite(c.eye) || !finite(c.target) || !finite(c.up) || !(glm::length(forward) > 0.0f))
        throw InputError(source + ": camera: eye and target must be finite and distinct");
    if (!(glm::length(glm::cross(forward, c.up)) > 0.0f))
        throw InputError(source + ": camera: up is parallel to the view direction");
    if (!(c.fovYDegrees > 0.0f && c.fovYDegrees < 180.0f))
        throw InputError(source + ": camera: fov must be between 0 and 180 degrees");
}

}  // namespace voxgi
