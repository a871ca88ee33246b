// libFuzzer target: .vdb reading (volumes/vdb_inspect.h inspectVdbFile and
// volumes/geometry_volume.h readGeometryVolume, OpenVDB underneath).
#include "tests/fuzz/fuzz_input.h"
#include "volumes/geometry_volume.h"
#include "volumes/vdb_inspect.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string path = voxgi::fuzz::asFile(data, size, ".vdb");
    voxgi::fuzz::expectOnlyInputErrors([&] { voxgi::inspectVdbFile(path); });
    voxgi::fuzz::expectOnlyInputErrors([&] { voxgi::readGeometryVolume(path); });
    return 0;
}
