#include "render/view/view_script.h"

#include <fstream>

#include <nlohmann/json.hpp>

#include "scenes/errors.h"

namespace voxgi::view {

namespace {

glm::vec3 readVec3(const nlohmann::json& key, const char* field, const std::string& where) {
    auto it = key.find(field);
    if (it == key.end() || !it->is_array() || it->size() != 3)
        throw InputError(where + ": '" + field + "' must be an array of 3 numbers");
    glm::vec3 v;
    for (int i = 0; i < 3; ++i) {
        if (!(*it)[std::size_t(i)].is_number()) throw InputError(where + ": '" + field + "' must hold numbers");
        v[i] = (*it)[std::size_t(i)].get<float>();
    }
    return v;
}

void check(const std::vector<CameraKey>& keys, const std::string& path) {
    if (keys.empty()) throw InputError(path + ": no camera keys");
    for (std::size_t i = 0; i < keys.size(); ++i) {
        if (i > 0 && keys[i].frame <= keys[i - 1].frame)
            throw InputError(path + ": keys[" + std::to_string(i) + "].frame must be larger than the previous key's");
        if (keys[i].eye == keys[i].target)
            throw InputError(path + ": keys[" + std::to_string(i) + "]: eye and target coincide");
    }
}

}  // namespace

ViewScript ViewScript::load(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw InputError(path + ": cannot open");
    nlohmann::json doc;
    try {
        doc = nlohmann::json::parse(in);
    } catch (const nlohmann::json::exception& e) {
        throw InputError(path + ": invalid JSON (" + e.what() + ")");
    }
    if (!doc.is_object() || !doc.contains("keys") || !doc["keys"].is_array())
        throw InputError(path + ": expected {\"keys\": [...]}");
    std::vector<CameraKey> keys;
    for (std::size_t i = 0; i < doc["keys"].size(); ++i) {
        const nlohmann::json& k = doc["keys"][i];
        std::string where = path + ": keys[" + std::to_string(i) + "]";
        if (!k.is_object() || !k.contains("frame") || !k["frame"].is_number_integer())
            throw InputError(where + ": 'frame' must be an integer");
        keys.push_back({k["frame"].get<int>(), readVec3(k, "eye", where), readVec3(k, "target", where)});
    }
    check(keys, path);
    ViewScript script;
    script.keys_ = std::move(keys);
    return script;
}

ViewScript ViewScript::fromKeys(std::vector<CameraKey> keys) {
    check(keys, "script");
    ViewScript script;
    script.keys_ = std::move(keys);
    return script;
}

void ViewScript::apply(int frame, Camera& camera) const {
    const CameraKey* a = &keys_.front();
    const CameraKey* b = a;
    for (std::size_t i = 0; i < keys_.size(); ++i) {
        if (keys_[i].frame <= frame) a = b = &keys_[i];
        if (keys_[i].frame > frame) {
            b = &keys_[i];
            break;
        }
    }
    float t = (b->frame > a->frame && frame > a->frame) ? float(frame - a->frame) / float(b->frame - a->frame) : 0.0f;
    if (frame < keys_.front().frame) b = a;  // before the first key: hold it
    camera.eye = glm::mix(a->eye, b->eye, t);
    camera.target = glm::mix(a->target, b->target, t);
}

}  // namespace voxgi::view
