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
    if (!doc.is_object() || (!doc.contains("keys") && !doc.contains("events")))
        throw InputError(path + ": expected {\"keys\": [...], \"events\": [...]}");
    if (doc.contains("keys") && !doc["keys"].is_array()) throw InputError(path + ": 'keys' must be an array");
    if (doc.contains("events") && !doc["events"].is_array()) throw InputError(path + ": 'events' must be an array");
    if (doc.value("keys", nlohmann::json::array()).empty() && doc.value("events", nlohmann::json::array()).empty())
        throw InputError(path + ": no camera keys and no events");
    std::vector<CameraKey> keys;
    for (std::size_t i = 0; doc.contains("keys") && i < doc["keys"].size(); ++i) {
        const nlohmann::json& k = doc["keys"][i];
        std::string where = path + ": keys[" + std::to_string(i) + "]";
        if (!k.is_object() || !k.contains("frame") || !k["frame"].is_number_integer())
            throw InputError(where + ": 'frame' must be an integer");
        keys.push_back({k["frame"].get<int>(), readVec3(k, "eye", where), readVec3(k, "target", where)});
    }
    check(keys, path);
    ViewScript script;
    script.keys_ = std::move(keys);
    for (std::size_t i = 0; doc.contains("events") && i < doc["events"].size(); ++i) {
        const nlohmann::json& e = doc["events"][i];
        std::string where = path + ": events[" + std::to_string(i) + "]";
        if (!e.is_object() || !e.contains("frame") || !e["frame"].is_number_integer() || e["frame"].get<int>() < 0)
            throw InputError(where + ": 'frame' must be an integer >= 0");
        ScriptEvent event;
        event.frame = e["frame"].get<int>();
        for (const char* kind : {"method", "action", "show"})
            if (e.contains(kind)) {
                if (!e[kind].is_string() || !event.kind.empty())
                    throw InputError(where + ": needs exactly one of method, action, show (a string)");
                event.kind = kind;
                event.value = e[kind].get<std::string>();
            }
        if (event.kind.empty()) throw InputError(where + ": needs one of method, action, show");
        if (event.kind == "action" && event.value != "screenshot" && event.value != "dump" &&
            event.value != "reload" && event.value != "animate_lights")
            throw InputError(where + ": unknown action '" + event.value +
                             "' (screenshot, dump, reload, animate_lights)");
        script.events_.push_back(event);
    }
    return script;
}

std::vector<ScriptEvent> ViewScript::eventsAt(int frame) const {
    std::vector<ScriptEvent> out;
    for (const ScriptEvent& e : events_)
        if (e.frame == frame) out.push_back(e);
    return out;
}

ViewScript ViewScript::fromKeys(std::vector<CameraKey> keys) {
    if (keys.empty()) throw InputError("script: no camera keys");
    check(keys, "script");
    ViewScript script;
    script.keys_ = std::move(keys);
    return script;
}

void ViewScript::apply(int frame, Camera& camera) const {
    if (keys_.empty()) return;
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
