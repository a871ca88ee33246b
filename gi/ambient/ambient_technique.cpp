#include "gi/ambient/ambient_technique.h"

#include <cmath>
#include <sstream>

#include "gl/program.h"
#include "scenes/errors.h"

namespace voxgi {

glm::vec3 readAmbientIrradiance(const GiSettings& gi) {
    gi.requireKnown("ambient", {"irradiance"});
    const std::string text = gi.getString("ambient.irradiance", "0");
    std::istringstream in(text);
    std::vector<float> values;
    std::string word;
    while (in >> word) {
        try {
            std::size_t used = 0;
            float v = std::stof(word, &used);
            if (used != word.size()) throw std::invalid_argument(word);
            values.push_back(v);
        } catch (const std::exception&) {
            throw InputError("gi.ambient.irradiance: expected \"r g b\" or one number, got '" + text + "'");
        }
    }
    if (values.size() != 1 && values.size() != 3)
        throw InputError("gi.ambient.irradiance: expected \"r g b\" or one number, got '" + text + "'");
    glm::vec3 e = values.size() == 1 ? glm::vec3(values[0]) : glm::vec3(values[0], values[1], values[2]);
    for (int c = 0; c < 3; ++c)
        if (!std::isfinite(e[c]) || e[c] < 0.0f)
            throw InputError("gi.ambient.irradiance: must be finite and non-negative, got '" + text + "'");
    return e;
}

namespace {

class AmbientTechnique final : public GiTechnique {
public:
    explicit AmbientTechnique(glm::vec3 irradiance)
        : irradiance_(irradiance), apply_(gl::Program::graphics("frame/fullscreen.vert", "ambient/apply.frag")) {}

    std::string name() const override { return "ambient"; }
    void update(const FrameInput&, const GBufferView&) override {}

    void applyIndirect(const FrameInput& input, const GBufferView& g) override {
        input.timers.begin("ambient.apply");
        apply_.use();
        const char* names[3] = {"uPosition", "uAlbedo", "uEmission"};
        const GLuint textures[3] = {g.position, g.albedo, g.emission};
        for (int i = 0; i < 3; ++i) {
            glBindTextureUnit(GLuint(i), textures[i]);
            apply_.set(names[i], i);
        }
        apply_.set("uIrradiance", irradiance_);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        input.timers.end();
    }

private:
    glm::vec3 irradiance_;
    gl::Program apply_;
};

}  // namespace

std::unique_ptr<GiTechnique> createAmbient(const Scene& scene) {
    return std::make_unique<AmbientTechnique>(readAmbientIrradiance(scene.gi));
}

}  // namespace voxgi
