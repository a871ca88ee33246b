// A camera path and timed events for scripted viewer runs (`voxgi view --script path.json`):
//   {"keys": [{"frame": 0, "eye": [x,y,z], "target": [x,y,z]}, {"frame": 30, ...}],
//    "events": [{"frame": 10, "method": "ddgi"}, {"frame": 12, "action": "dump"},
//               {"frame": 0, "show": "probes"}]}
// The camera moves linearly between keys and holds the last one; frames before the first key
// use the first key. Either list may be absent, not both. Events run before their frame renders,
// as if the key or panel control had been used: "method" switches the GI method, "action" is
// one of screenshot, dump, reload, animate_lights (toggle), "show" a display mode or debug view
// name (viewer_state.h applyShow).
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scenes/scene.h"

namespace voxgi::view {

struct CameraKey {
    int frame = 0;
    glm::vec3 eye{0.0f};
    glm::vec3 target{0.0f};
};

struct ScriptEvent {
    int frame = 0;
    std::string kind;   // "method", "action" or "show"
    std::string value;
};

class ViewScript {
public:
    // Throws InputError("<path>: <problem>") for an unreadable file, bad JSON, missing or
    // malformed fields, no keys, or frames not strictly increasing.
    static ViewScript load(const std::string& path);
    static ViewScript fromKeys(std::vector<CameraKey> keys);  // same checks, path "script"

    // Eye and target at `frame` (no keys: unchanged); the camera's up, lens and size are kept.
    void apply(int frame, Camera& camera) const;
    const std::vector<CameraKey>& keys() const { return keys_; }
    // The events of `frame`, in file order.
    std::vector<ScriptEvent> eventsAt(int frame) const;

private:
    std::vector<CameraKey> keys_;
    std::vector<ScriptEvent> events_;
};

}  // namespace voxgi::view
