// How much memory a command may plan to use: work whose estimate exceeds it is refused before
// anything is allocated, with the estimate and the limit in the message, instead of ending in
// the kernel's OOM killer. Default: three quarters of physical memory; `voxgi --max-memory GIB`
// or $VOXGI_MAX_MEMORY (GiB) sets it.
#pragma once

#include <cstdint>
#include <string>

namespace voxgi {

std::uint64_t memoryLimit();
void setMemoryLimit(std::uint64_t bytes);
// InputError "<what> needs about X GiB; the memory limit is Y GiB (--max-memory)" when bytes
// exceeds the limit.
void requireMemory(double bytes, const std::string& what);

}  // namespace voxgi
