// Owning handles for GL objects (DSA style, GL 4.5). Move-only; deleted with their owner.
#pragma once

#include <cstddef>
#include <initializer_list>
#include <utility>
#include <vector>

#include <epoxy/gl.h>

namespace voxgi::gl {

class Handle {
public:
    using Deleter = void (*)(GLuint);
    Handle() = default;
    Handle(GLuint id, Deleter deleter) : id_(id), deleter_(deleter) {}
    ~Handle() { reset(); }
    Handle(Handle&& o) noexcept : id_(std::exchange(o.id_, 0)), deleter_(o.deleter_) {}
    Handle& operator=(Handle&& o) noexcept {
        if (this != &o) {
            reset();
            id_ = std::exchange(o.id_, 0);
            deleter_ = o.deleter_;
        }
        return *this;
    }
    Handle(const Handle&) = delete;
    Handle& operator=(const Handle&) = delete;
    GLuint id() const { return id_; }
    explicit operator bool() const { return id_ != 0; }
    void reset() {
        if (id_ && deleter_) deleter_(id_);
        id_ = 0;
    }

private:
    GLuint id_ = 0;
    Deleter deleter_ = nullptr;
};

// A 2D texture (or 2D array / 3D / cube, by target) with immutable storage.
Handle createTexture(GLenum target, GLenum internalFormat, int width, int height, int depth = 1,
                     int levels = 1);
Handle createBuffer(std::size_t bytes, const void* data = nullptr, GLbitfield flags = GL_DYNAMIC_STORAGE_BIT);
// Makes `buffer` hold at least `bytes` (at least 16), growing it to `growth` times the request
// when it is too small (twice: sizes changing frame by frame settle; 1 for large buffers whose
// size changes rarely); `capacity` tracks its size.
void ensureBuffer(Handle& buffer, std::size_t& capacity, std::size_t bytes, double growth = 2.0);
Handle createFramebuffer();
Handle createVertexArray();
// A sampler object: bound to a unit, its filtering and comparison override the texture's.
Handle createSampler();
// A GL_TIME_ELAPSED query object.
Handle createTimerQuery();
// Its result in milliseconds; waits for it (call after the bracketed work is finished).
double timerQueryMs(GLuint query);
// A framebuffer drawing to `colors` (attachments 0.., all enabled as draw buffers) with an
// optional `depth` texture (0 = none); throws GlError naming `what` if incomplete.
Handle createFramebuffer(std::initializer_list<GLuint> colors, GLuint depth, const char* what);
// Throws GlError naming `what` unless the framebuffer is complete.
void checkFramebuffer(GLuint framebuffer, const char* what);

// Reads a whole RGBA32F (or R32F with channels = 1) texture level back to the CPU.
std::vector<float> readTexture(GLuint texture, int width, int height, int channels);

}  // namespace voxgi::gl
