#include "gl/program.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <glm/gtc/type_ptr.hpp>

#include "gl/context.h"

namespace voxgi::gl {

namespace fs = std::filesystem;

std::string shaderRoot() {
    const char* env = std::getenv("VOXGI_SHADER_DIR");
    return env && *env ? std::string(env) : std::string(VOXGI_SHADER_DIR);
}

namespace {

// The root-relative path of `include` named in `includer`: beside the includer when such a file
// exists (the shared headers include each other by bare name, as C++ does), else from the root.
std::string resolveInclude(const std::string& includer, const std::string& include) {
    const std::string beside = (fs::path(includer).parent_path() / include).lexically_normal().generic_string();
    return fs::is_regular_file(fs::path(shaderRoot()) / beside) ? beside : include;
}

// Where library headers named in <...> are: $VOXGI_SYSTEM_SHADER_INCLUDE when set (a bundle
// carries PNanoVDB.h, scripts/bundle.sh), otherwise the build machine's include directory.
std::string systemShaderIncludeDir() {
    const char* env = std::getenv("VOXGI_SYSTEM_SHADER_INCLUDE");
    return env && *env ? std::string(env) : std::string(VOXGI_SYSTEM_SHADER_INCLUDE);
}

// The absolute path of a library header named in <...>, or "" when it is not installed.
std::string systemShaderInclude(const std::string& include) {
    const fs::path full = fs::path(systemShaderIncludeDir()) / include;
    return fs::is_regular_file(full) ? full.generic_string() : std::string();
}

// Source-string numbers for #line: 0 is the main file, includes count up from 1.
void expand(const std::string& relative, std::set<std::string>& seen, std::vector<std::string>& files,
            std::ostringstream& out, int depth) {
    if (depth > 32) throw GlError("shader include depth exceeded at " + relative);
    fs::path full = fs::path(shaderRoot()) / relative;
    std::ifstream in(full);
    if (!in) throw GlError("shader file not found: " + full.string());
    int fileIndex = int(files.size());
    files.push_back(relative);
    std::string line;
    int lineNo = 0;
    while (std::getline(in, line)) {
        ++lineNo;
        auto first = line.find_first_not_of(" \t");
        if (first != std::string::npos && line.compare(first, 8, "#include") == 0 &&
            line.find("<nanovdb/", first) != std::string::npos) {
            // A header from a library that ships GLSL (NanoVDB's PNanoVDB.h), by absolute path.
            // Other <...> includes (C headers inside PNanoVDB.h's C branches) pass through for
            // the GLSL preprocessor to skip.
            auto a = line.find('<', first), b = line.rfind('>');
            if (b == std::string::npos || b <= a) throw GlError(relative + ":" + std::to_string(lineNo) + ": bad #include");
            const std::string inc = systemShaderInclude(line.substr(a + 1, b - a - 1));
            if (inc.empty())
                throw GlError(relative + ":" + std::to_string(lineNo) + ": " + line.substr(a, b - a + 1) +
                              " not found in " + systemShaderIncludeDir());
            if (seen.insert(inc).second) expand(inc, seen, files, out, depth + 1);
            out << "#line " << lineNo + 1 << " " << fileIndex << "\n";
            continue;
        }
        if (first != std::string::npos && line.compare(first, 8, "#include") == 0 &&
            line.find('<', first) == std::string::npos) {
            auto a = line.find('"', first), b = line.rfind('"');
            if (a == std::string::npos || b <= a) throw GlError(relative + ":" + std::to_string(lineNo) + ": bad #include");
            std::string inc = resolveInclude(relative, line.substr(a + 1, b - a - 1));
            if (seen.insert(inc).second) expand(inc, seen, files, out, depth + 1);
            out << "#line " << lineNo + 1 << " " << fileIndex << "\n";
            continue;
        }
        out << line << "\n";
        if (lineNo == 1 && line.rfind("#version", 0) == 0) out << "#line 2 " << fileIndex << "\n";
    }
}

GLuint compileStage(GLenum stage, const std::string& path, const Program::Defines& defines) {
    std::string source = preprocessShader(path, defines);
    GLuint shader = glCreateShader(stage);
    const char* src = source.c_str();
    glShaderSource(shader, 1, &src, nullptr);
    glCompileShader(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        GLint len = 0;
        glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &len);
        std::string log(std::size_t(len > 0 ? len : 1), '\0');
        glGetShaderInfoLog(shader, len, nullptr, log.data());
        glDeleteShader(shader);
        throw GlError("shader " + path + " failed to compile: " + log);
    }
    return shader;
}

GLuint link(const std::vector<GLuint>& stages, const std::string& name) {
    GLuint program = glCreateProgram();
    for (GLuint s : stages) glAttachShader(program, s);
    glLinkProgram(program);
    for (GLuint s : stages) glDeleteShader(s);
    GLint ok = 0;
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (!ok) {
        GLint len = 0;
        glGetProgramiv(program, GL_INFO_LOG_LENGTH, &len);
        std::string log(std::size_t(len > 0 ? len : 1), '\0');
        glGetProgramInfoLog(program, len, nullptr, log.data());
        glDeleteProgram(program);
        throw GlError("program " + name + " failed to link: " + log);
    }
    return program;
}

}  // namespace

std::string preprocessShader(const std::string& relativePath, const Program::Defines& defines) {
    std::set<std::string> seen{relativePath};
    std::vector<std::string> files;
    std::ostringstream body;
    expand(relativePath, seen, files, body, 0);
    std::string text = body.str();
    if (text.rfind("#version", 0) != 0) throw GlError(relativePath + ": first line must be #version");
    auto eol = text.find('\n');
    std::ostringstream defs;
    for (const auto& [name, value] : defines) defs << "#define " << name << " " << value << "\n";
    return text.substr(0, eol + 1) + defs.str() + text.substr(eol + 1);
}

Program::~Program() {
    if (id_) glDeleteProgram(id_);
}

Program& Program::operator=(Program&& other) noexcept {
    if (this != &other) {
        if (id_) glDeleteProgram(id_);
        id_ = std::exchange(other.id_, 0);
        name_ = std::move(other.name_);
    }
    return *this;
}

Program Program::graphics(const std::string& vertexPath, const std::string& fragmentPath, const Defines& defines) {
    Program p;
    p.name_ = vertexPath + " + " + fragmentPath;
    GLuint vs = compileStage(GL_VERTEX_SHADER, vertexPath, defines);
    GLuint fs;
    try {
        fs = compileStage(GL_FRAGMENT_SHADER, fragmentPath, defines);
    } catch (...) {
        glDeleteShader(vs);
        throw;
    }
    p.id_ = link({vs, fs}, p.name_);
    return p;
}

Program Program::withGeometry(const std::string& vertexPath, const std::string& geometryPath,
                              const std::string& fragmentPath, const Defines& defines) {
    Program p;
    p.name_ = vertexPath + " + " + geometryPath + " + " + fragmentPath;
    std::vector<GLuint> stages;
    try {
        stages.push_back(compileStage(GL_VERTEX_SHADER, vertexPath, defines));
        stages.push_back(compileStage(GL_GEOMETRY_SHADER, geometryPath, defines));
        stages.push_back(compileStage(GL_FRAGMENT_SHADER, fragmentPath, defines));
    } catch (...) {
        for (GLuint s : stages) glDeleteShader(s);
        throw;
    }
    p.id_ = link(stages, p.name_);
    return p;
}

Program Program::compute(const std::string& path, const Defines& defines) {
    Program p;
    p.name_ = path;
    p.id_ = link({compileStage(GL_COMPUTE_SHADER, path, defines)}, path);
    return p;
}

void Program::set(const char* name, const glm::mat4& m) const {
    glProgramUniformMatrix4fv(id_, location(name), 1, GL_FALSE, glm::value_ptr(m));
}

void Program::set(const char* name, const glm::mat3& m) const {
    glProgramUniformMatrix3fv(id_, location(name), 1, GL_FALSE, glm::value_ptr(m));
}

}  // namespace voxgi::gl
