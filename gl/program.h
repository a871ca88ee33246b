// GLSL programs built from files under shaders/, with `#include "path"` resolved like C's
// quoted includes (beside the including file first, then against the shader root; each file
// once) and `#line` kept right so compile errors name the real file. `#include <...>` lines are
// left to the GLSL preprocessor: only the C++ side of a shaders/shared/ header has them, inside
// `#ifdef __cplusplus`.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <epoxy/gl.h>
#include <glm/glm.hpp>

namespace voxgi::gl {

// The shader root: $VOXGI_SHADER_DIR when set, otherwise the source tree's shaders/.
std::string shaderRoot();

// Reads `relativePath` under the shader root with includes expanded; `defines` are inserted
// after the #version line as `#define NAME VALUE`. Throws GlError on a missing file.
std::string preprocessShader(const std::string& relativePath,
                             const std::vector<std::pair<std::string, std::string>>& defines = {});

class Program {
public:
    Program() = default;
    ~Program();
    Program(Program&& other) noexcept : id_(std::exchange(other.id_, 0)), name_(std::move(other.name_)) {}
    Program& operator=(Program&& other) noexcept;
    Program(const Program&) = delete;
    Program& operator=(const Program&) = delete;

    using Defines = std::vector<std::pair<std::string, std::string>>;
    // Graphics program from a vertex and a fragment shader file.
    static Program graphics(const std::string& vertexPath, const std::string& fragmentPath,
                            const Defines& defines = {});
    // Graphics program with a geometry shader between the vertex and fragment shaders.
    static Program withGeometry(const std::string& vertexPath, const std::string& geometryPath,
                                const std::string& fragmentPath, const Defines& defines = {});
    // Compute program from one file.
    static Program compute(const std::string& path, const Defines& defines = {});

    GLuint id() const { return id_; }
    void use() const { glUseProgram(id_); }
    GLint location(const char* name) const { return glGetUniformLocation(id_, name); }

    void set(const char* name, int v) const { glProgramUniform1i(id_, location(name), v); }
    void set(const char* name, unsigned v) const { glProgramUniform1ui(id_, location(name), v); }
    void set(const char* name, float v) const { glProgramUniform1f(id_, location(name), v); }
    void set(const char* name, glm::vec2 v) const { glProgramUniform2f(id_, location(name), v.x, v.y); }
    void set(const char* name, glm::vec3 v) const { glProgramUniform3f(id_, location(name), v.x, v.y, v.z); }
    void set(const char* name, glm::vec4 v) const { glProgramUniform4f(id_, location(name), v.x, v.y, v.z, v.w); }
    void set(const char* name, glm::ivec2 v) const { glProgramUniform2i(id_, location(name), v.x, v.y); }
    void set(const char* name, glm::ivec3 v) const { glProgramUniform3i(id_, location(name), v.x, v.y, v.z); }
    void set(const char* name, const glm::mat4& m) const;
    void set(const char* name, const glm::mat3& m) const;

private:
    GLuint id_ = 0;
    std::string name_;
};

}  // namespace voxgi::gl
