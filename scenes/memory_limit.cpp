#include "scenes/memory_limit.h"

#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>

#include "scenes/errors.h"

namespace voxgi {

namespace {
constexpr double kGiB = 1024.0 * 1024.0 * 1024.0;

std::uint64_t defaultLimit() {
    if (const char* env = std::getenv("VOXGI_MAX_MEMORY")) {
        char* end = nullptr;
        const double gib = std::strtod(env, &end);
        if (end != env && *end == '\0' && gib > 0.0) return std::uint64_t(gib * kGiB);
    }
    const long pages = ::sysconf(_SC_PHYS_PAGES), size = ::sysconf(_SC_PAGE_SIZE);
    if (pages <= 0 || size <= 0) return std::uint64_t(8.0 * kGiB);
    return std::uint64_t(pages) * std::uint64_t(size) / 4 * 3;
}

std::atomic<std::uint64_t>& limit() {
    static std::atomic<std::uint64_t> value{defaultLimit()};
    return value;
}
}  // namespace

std::uint64_t memoryLimit() { return limit().load(); }

void setMemoryLimit(std::uint64_t bytes) { limit().store(bytes); }

void requireMemory(double bytes, const std::string& what) {
    if (!(bytes > double(memoryLimit()))) return;
    char text[160];
    std::snprintf(text, sizeof text, " needs about %.1f GiB; the memory limit is %.1f GiB (--max-memory)", bytes / kGiB,
                  double(memoryLimit()) / kGiB);
    throw InputError(what + text);
}

}  // namespace voxgi
