// Shared by the fuzz targets: the input as a file (the readers under test take paths), and the
// rule that only InputError may leave a reader; anything else (a crash, a sanitizer report, an
// out-of-memory abort from libFuzzer's -rss_limit_mb) is a finding.
#pragma once

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "scenes/errors.h"
#include "scenes/memory_limit.h"

namespace voxgi::fuzz {

// Readers refuse what their memory estimate puts over the limit; 1 GiB keeps that under
// libFuzzer's 2 GiB -rss_limit_mb, so only an allocation nobody estimated is a finding.
inline const bool kMemoryLimitSet = (setMemoryLimit(std::uint64_t(1) << 30), true);

// A per-process scratch file with the given extension holding the input.
inline std::string asFile(const std::uint8_t* data, std::size_t size, const std::string& extension) {
    const std::string path = "/tmp/voxgi-fuzz-" + std::to_string(::getpid()) + extension;
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) std::abort();
    if (size > 0 && std::fwrite(data, 1, size, f) != size) std::abort();
    std::fclose(f);
    return path;
}

template <typename Read>
void expectOnlyInputErrors(Read&& read) {
    try {
        read();
    } catch (const InputError&) {
        // A refused input: the expected outcome for most fuzz inputs.
    }
}

}  // namespace voxgi::fuzz
