// A few bytes a kernel wrote (counters, a job count) read back frames later without waiting for
// the GPU. Each push copies them, on the GPU, into its own slot of a persistently mapped buffer
// and fences the copy; latest() hands back the newest slot whose fence has passed. With `slots`
// copies in flight the CPU runs at most that many pushes ahead: a push that finds its slot still
// pending waits for it (the GPU is that far behind).
#pragma once

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <vector>

#include "gl/resources.h"

namespace voxgi::gl {

class ReadbackRing {
public:
    // `bytes` per push (the ranges of one push together), `slots` pushes in flight.
    explicit ReadbackRing(std::size_t bytes, int slots = 3);
    ~ReadbackRing();
    ReadbackRing(const ReadbackRing&) = delete;
    ReadbackRing& operator=(const ReadbackRing&) = delete;

    struct Range {
        GLuint buffer;
        std::size_t offset, bytes;
    };
    // Queues copies of `ranges` (back to back in the slot) tagged `tag`. Writes by shaders to
    // those buffers must be made visible first (glMemoryBarrier GL_BUFFER_UPDATE_BARRIER_BIT).
    void push(std::uint64_t tag, std::initializer_list<Range> ranges);
    // The newest finished push's tag and bytes (into out, `bytes` long), without waiting; false
    // when none has finished since the last call that returned one.
    bool latest(std::uint64_t& tag, void* out);
    // Waits for every queued push, then as latest(): the last push's bytes.
    bool finish(std::uint64_t& tag, void* out);

private:
    struct Slot {
        GLsync fence = nullptr;
        std::uint64_t tag = 0;
    };
    // Takes slot `s` (finished) as the newest if it is newer than what is kept.
    void harvest(std::size_t s);
    std::size_t bytes_;
    Handle buffer_;
    const std::uint8_t* mapped_ = nullptr;
    std::vector<Slot> slots_;
    std::size_t next_ = 0;
    std::vector<std::uint8_t> newest_;
    std::uint64_t newestTag_ = 0;
    bool haveNewest_ = false;
};

}  // namespace voxgi::gl
