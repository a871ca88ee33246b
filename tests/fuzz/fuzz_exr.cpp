// libFuzzer target: EXR reading (scenes/image.h readExr, OpenEXR underneath).
#include "scenes/image.h"
#include "tests/fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string path = voxgi::fuzz::asFile(data, size, ".exr");
    voxgi::fuzz::expectOnlyInputErrors([&] { voxgi::readExr(path); });
    return 0;
}
