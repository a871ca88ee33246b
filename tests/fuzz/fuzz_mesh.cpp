// libFuzzer target: mesh import through assimp (scenes/mesh_import.h). The first byte picks the
// format (OBJ, PLY, glTF), the rest is the file.
#include <glm/glm.hpp>

#include "scenes/mesh_import.h"
#include "tests/fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size < 1) return 0;
    static const char* const kExtensions[] = {".obj", ".ply", ".gltf"};
    const std::string path = voxgi::fuzz::asFile(data + 1, size - 1, kExtensions[data[0] % 3]);
    voxgi::fuzz::expectOnlyInputErrors([&] {
        voxgi::Scene scene;
        voxgi::importMeshFile(path, glm::mat4(1.0f), scene, 0);
    });
    return 0;
}
