// A camera path for scripted viewer runs (`voxgi view --script path.json`):
//   {"keys": [{"frame": 0, "eye": [x,y,z], "target": [x,y,z]}, {"frame": 30, ...}]}
// The camera moves linearly between keys and holds the last one; frames before the first key
// use the first key.
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

class ViewScript {
public:
    // Throws InputError("<path>: <problem>") for an unreadable file, bad JSON, missing or
    // malformed fields, no keys, or frames not strictly increasing.
    static ViewScript load(const std::string& path);
    static ViewScript fromKeys(std::vector<CameraKey> keys);  // same checks, path "script"

    // Eye and target at `frame`; the camera's up, lens and size are kept.
    void apply(int frame, Camera& camera) const;
    const std::vector<CameraKey>& keys() const { return keys_; }

private:
    std::vector<CameraKey> keys_;
};

}  // namespace voxgi::view
