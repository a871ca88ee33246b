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

// Tone-maps one RGB layer (exposure in stops, ACES filmic fit, sRGB) to an 8-bit PNG.
void writePng(const std::string& path, const Image& image, const std::string& layer = "beauty",
              float exposureStops = 0.0f);
// Writes 8-bit RGB pixels (top row first) to PNG atomically.
void writePngRgb8(const std::string& path, int width, int height, const std::vector<std::uint8_t>& rgb);

// The tone curve used for previews: ACES filmic fit (Narkowicz 2015) then the sRGB transfer.
glm::vec3 toneMapToSrgb(glm::vec3 linear, float exposureStops);


}  // namespace voxgi
