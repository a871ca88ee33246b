#include "gi/ambient/ambient_technique.h"

#include "gl/program.h"
#include "gl/screen_pass.h"

namespace voxgi {

const SettingsTable<AmbientDesc>& ambientSettings() {
    static const SettingsTable<AmbientDesc> table = [] {
        SettingsTable<AmbientDesc> t("ambient");
        t.triple("irradiance", &AmbientDesc::irradiance, 0.0, 1e30, "constant irradiance on every surface (W/m^2 per colour)")
            .main();
        return t;
    }();
    return table;
}

namespace {

class AmbientTechnique final : public GiTechnique {
public:
    explicit AmbientTechnique(glm::vec3 irradiance)
        : irradiance_(irradiance), apply_(gl::Program::compute("ambient/apply.comp")) {}

    std::string name() const override { return "ambient"; }
    void update(const FrameInput&, const GBufferView&) override {}

    void applyIndirect(const FrameInput& input, const GBufferView& g) override {
        if (!input.plan.runs("ambient.apply")) return;
        input.timers.begin("ambient.apply");
        apply_.use();
        const char* names[3] = {"uPosition", "uAlbedo", "uEmission"};
        const GLuint textures[3] = {g.position, g.albedo, g.emission};
        for (int i = 0; i < 3; ++i) {
            glBindTextureUnit(GLuint(i), textures[i]);
            apply_.set(names[i], i);
        }
        apply_.set("uIrradiance", irradiance_);
        gl::addToBoundTarget(apply_);
        input.timers.end();
    }

private:
    glm::vec3 irradiance_;
    gl::Program apply_;
};

}  // namespace

std::unique_ptr<GiTechnique> createAmbientTechnique(const AmbientDesc& desc) {
    return std::make_unique<AmbientTechnique>(desc.irradiance);
}

}  // namespace voxgi
