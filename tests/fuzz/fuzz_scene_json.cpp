// libFuzzer target: the scene JSON parser (scenes/scene_loader.h).
#include <string>

#include "scenes/scene_loader.h"
#include "tests/fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    voxgi::fuzz::expectOnlyInputErrors([&] {
        voxgi::Scene scene = voxgi::parseSceneJson(text, "/tmp/voxgi-fuzz-scene.json");
        voxgi::requireRenderable(scene, "fuzz");
    });
    return 0;
}
