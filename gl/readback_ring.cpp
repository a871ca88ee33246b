#include "gl/readback_ring.h"

#include <cstring>
#include <stdexcept>

namespace voxgi::gl {

namespace {
constexpr GLbitfield kMapFlags = GL_MAP_READ_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;

bool finished(GLsync fence, GLuint64 timeoutNs) {
    const GLenum r = glClientWaitSync(fence, timeoutNs > 0 ? GL_SYNC_FLUSH_COMMANDS_BIT : 0, timeoutNs);
    if (r == GL_WAIT_FAILED) throw std::runtime_error("ReadbackRing: glClientWaitSync failed");
    return r == GL_ALREADY_SIGNALED || r == GL_CONDITION_SATISFIED;
}

void waitFor(GLsync fence) {
    // A wait that times out (a second) is tried again: the GPU is behind, not gone.
    while (!finished(fence, 1000000000ull)) {
    }
}
}  // namespace

ReadbackRing::ReadbackRing(std::size_t bytes, int slots)
    : bytes_(bytes), slots_(std::size_t(slots > 0 ? slots : 1)), newest_(bytes) {
    buffer_ = createBuffer(bytes_ * slots_.size(), nullptr, kMapFlags);
    mapped_ = static_cast<const std::uint8_t*>(
        glMapNamedBufferRange(buffer_.id(), 0, GLsizeiptr(bytes_ * slots_.size()), kMapFlags));
    if (!mapped_) throw std::runtime_error("ReadbackRing: could not map its buffer persistently");
}

ReadbackRing::~ReadbackRing() {
    for (Slot& s : slots_)
        if (s.fence) glDeleteSync(s.fence);
    if (buffer_) glUnmapNamedBuffer(buffer_.id());
}

void ReadbackRing::harvest(std::size_t s) {
    Slot& slot = slots_[s];
    if (!haveNewest_ || slot.tag >= newestTag_) {
        std::memcpy(newest_.data(), mapped_ + s * bytes_, bytes_);
        newestTag_ = slot.tag;
        haveNewest_ = true;
    }
    glDeleteSync(slot.fence);
    slot.fence = nullptr;
}

void ReadbackRing::push(std::uint64_t tag, std::initializer_list<Range> ranges) {
    std::size_t total = 0;
    for (const Range& r : ranges) total += r.bytes;
    if (total > bytes_) throw std::logic_error("ReadbackRing::push: more bytes than a slot holds");
    const std::size_t s = next_++ % slots_.size();
    if (slots_[s].fence) {
        waitFor(slots_[s].fence);
        harvest(s);
    }
    std::size_t at = s * bytes_;
    for (const Range& r : ranges) {
        glCopyNamedBufferSubData(r.buffer, buffer_.id(), GLintptr(r.offset), GLintptr(at), GLsizeiptr(r.bytes));
        at += r.bytes;
    }
    glMemoryBarrier(GL_CLIENT_MAPPED_BUFFER_BARRIER_BIT);
    slots_[s].tag = tag;
    slots_[s].fence = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
    glFlush();  // so the fence can pass while the CPU does other work
}

bool ReadbackRing::latest(std::uint64_t& tag, void* out) {
    for (std::size_t s = 0; s < slots_.size(); ++s)
        if (slots_[s].fence && finished(slots_[s].fence, 0)) harvest(s);
    if (!haveNewest_) return false;
    tag = newestTag_;
    std::memcpy(out, newest_.data(), bytes_);
    haveNewest_ = false;
    return true;
}

bool ReadbackRing::finish(std::uint64_t& tag, void* out) {
    for (std::size_t s = 0; s < slots_.size(); ++s)
        if (slots_[s].fence) {
            waitFor(slots_[s].fence);
            harvest(s);
        }
    return latest(tag, out);
}

}  // namespace voxgi::gl
