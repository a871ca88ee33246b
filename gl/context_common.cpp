#include <cstdio>
#include <cstdlib>
#include <cstring>

#include <epoxy/gl.h>

#include "gl/context.h"

namespace voxgi::gl {

namespace {

const char* severityName(GLenum severity) {
    switch (severity) {
        case GL_DEBUG_SEVERITY_HIGH: return "high";
        case GL_DEBUG_SEVERITY_MEDIUM: return "medium";
        case GL_DEBUG_SEVERITY_LOW: return "low";
        default: return "note";
    }
}

void GLAPIENTRY debugCallback(GLenum source, GLenum type, GLuint id, GLenum severity,
                              GLsizei length, const GLchar* message, const void* user) {
    // Notifications are noise on every driver; VOXGI_GL_DEBUG=all shows them too.
    static const bool all = [] {
        const char* v = std::getenv("VOXGI_GL_DEBUG");
        return v && std::strcmp(v, "all") == 0;
    }();
    if (severity == GL_DEBUG_SEVERITY_NOTIFICATION && !all) return;
    // Compiler messages too: a failed compile throws GlError with its log (gl/program.cpp), and
    // Mesa reports every warning as high severity (NanoVDB's PNanoVDB.h alone makes 21).
    if (source == GL_DEBUG_SOURCE_SHADER_COMPILER && !all) return;
    std::fprintf(stderr, "voxgi: gl debug [%s] (id %u): %.*s\n", severityName(severity), id,
                 int(length < 0 ? std::strlen(message) : std::size_t(length)), message);
}

}  // namespace

void Context::finishSetup(const ContextDesc& desc, const std::string& via) {
    int version = epoxy_gl_version();
    if (version < 45 || epoxy_is_desktop_gl() == 0) {
        throw GlError("OpenGL 4.5 core is required but " + via + " gives version " +
                      std::to_string(version / 10) + "." + std::to_string(version % 10));
    }
    if (desc.debugOutput) {
        glEnable(GL_DEBUG_OUTPUT);
        glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
        glDebugMessageCallback(debugCallback, nullptr);
    }
    const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    const char* ver = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    description_ = std::string(renderer ? renderer : "?") + " / OpenGL " + (ver ? ver : "?") + " via " + via;
}

}  // namespace voxgi::gl
