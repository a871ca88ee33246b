// Images as linear float layers (beauty, direct, indirect, albedo, normal, depth...), written as
// one multi-layer OpenEXR file, read back for comparisons, and previewed as tone-mapped PNG.
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace voxgi {

struct ImageLayer {
    std::string name;      // "beauty" is written as plain R, G, B; others as name.R ... or name.Z
    int channels = 3;      // 3 (RGB) or 1 (Z)
    std::vector<float> data;  // row-major, top row first, `channels` floats per pixel
};

class Image {
public:
    Image() = default;
    Image(int width, int height) : width_(width), height_(height) {}

    int width() const { return width_; }
    int height() const { return height_; }
    std::size_t pixelCount() const { return std::size_t(width_) * std::size_t(height_); }

    // Creates the layer (zero-filled) when absent.
    ImageLayer& layer(const std::string& name, int channels = 3);
    const ImageLayer* find(const std::string& name) const;
    const std::vector<ImageLayer>& layers() const { return layers_; }

    glm::vec3 rgb(const std::string& name, int x, int y) const;
    void setRgb(const std::string& name, int x, int y, glm::vec3 value);

    // How the image is meant to be shown (the PNG written beside it): stored in the EXR header
    // as the float attribute voxgiExposureStops and the string voxgiToneCurve when set.
    struct Display {
        bool set = false;
        float exposureStops = 0.0f;
        int toneCurve = 0;  // shading::kToneFilmic or kToneReinhard (shaders/shared/tone_map.h)
    };
    Display display;

private:
    int width_ = 0;
    int height_ = 0;
    std::vector<ImageLayer> layers_;
};

// Writes every layer as 32-bit float channels. The file appears atomically (temporary + rename).
void writeExr(const std::string& path, const Image& image);
// Reads an EXR written by voxgi or any tool: R,G,B become "beauty", "x.R/G/B" become layer "x",
// a lone "x.Z" or "Z" a 1-channel layer. Throws InputError on failure.
Image readExr(const std::string& path);

// Tone-maps one RGB layer to an 8-bit PNG: exposure in stops, then the tone curve and the sRGB
// transfer of shaders/shared/tone_map.h (toneCurve: shading::kToneFilmic or kToneReinhard).
void writePng(const std::string& path, const Image& image, const std::string& layer = "beauty",
              float exposureStops = 0.0f, int toneCurve = 0);
// Writes 8-bit RGB pixels (top row first) to PNG atomically.
void writePngRgb8(const std::string& path, int width, int height, const std::vector<std::uint8_t>& rgb);

// One pixel through that display transform (non-finite values show as black).
glm::vec3 toneMapToSrgb(glm::vec3 linear, float exposureStops, int toneCurve = 0);

// The exposure (stops) that maps the log-average luminance of the layer's lit pixels (luminance
// above zero: the background of a scene without sky does not count) to middle grey (0.18);
// 0 when no pixel is lit. Clamped to [-30, 30].
float autoExposureStops(const Image& image, const std::string& layer = "beauty");
// The viewer's eye adaptation: `current` moves toward `target` (stops) with time constant
// `tauSeconds` over `dtSeconds`, exponentially, so a view that turns does not flicker.
float adaptExposure(float current, float target, float dtSeconds, float tauSeconds);
// "filmic" or "reinhard" for a shading::kTone* value, and back (-1 for an unknown name).
const char* toneCurveName(int toneCurve);
int toneCurveFromName(const std::string& name);


}  // namespace voxgi
