#include "scenes/image.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <map>

#include <ImfChannelList.h>
#include <ImfFloatAttribute.h>
#include <ImfStringAttribute.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImathBox.h>

#include "scenes/atomic_file.h"
#include "scenes/errors.h"
#include "scenes/memory_limit.h"
#include "shaders/shared/tone_map.h"

#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>

namespace voxgi {

namespace fs = std::filesystem;

ImageLayer& Image::layer(const std::string& name, int channels) {
    for (ImageLayer& l : layers_)
        if (l.name == name) return l;
    ImageLayer l;
    l.name = name;
    l.channels = channels;
    l.data.assign(pixelCount() * std::size_t(channels), 0.0f);
    layers_.push_back(std::move(l));
    return layers_.back();
}

const ImageLayer* Image::find(const std::string& name) const {
    for (const ImageLayer& l : layers_)
        if (l.name == name) return &l;
    return nullptr;
}

glm::vec3 Image::rgb(const std::string& name, int x, int y) const {
    const ImageLayer* l = find(name);
    if (!l) return glm::vec3(0.0f);
    std::size_t i = (std::size_t(y) * std::size_t(width_) + std::size_t(x)) * std::size_t(l->channels);
    if (l->channels == 1) return glm::vec3(l->data[i]);
    return {l->data[i], l->data[i + 1], l->data[i + 2]};
}

void Image::setRgb(const std::string& name, int x, int y, glm::vec3 v) {
    ImageLayer& l = layer(name, 3);
    std::size_t i = (std::size_t(y) * std::size_t(width_) + std::size_t(x)) * 3;
    l.data[i] = v.x;
    l.data[i + 1] = v.y;
    l.data[i + 2] = v.z;
}

namespace {
const char* kRgb[3] = {"R", "G", "B"};
}  // namespace

void writeExr(const std::string& path, const Image& image) {
    Imf::Header header(image.width(), image.height());
    Imf::FrameBuffer fb;
    const std::size_t xStride = sizeof(float);
    for (const ImageLayer& l : image.layers()) {
        for (int c = 0; c < l.channels; ++c) {
            std::string name = l.channels == 1 ? (l.name == "depth" ? std::string("Z") : l.name + ".Y")
                                               : (l.name == "beauty" ? std::string(kRgb[c]) : l.name + "." + kRgb[c]);
            header.channels().insert(name, Imf::Channel(Imf::FLOAT));
            char* base = reinterpret_cast<char*>(const_cast<float*>(l.data.data())) + std::size_t(c) * sizeof(float);
            fb.insert(name, Imf::Slice(Imf::FLOAT, base, xStride * std::size_t(l.channels),
                                       xStride * std::size_t(l.channels) * std::size_t(image.width())));
        }
    }
    if (image.display.set) {
        header.insert("voxgiExposureStops", Imf::FloatAttribute(image.display.exposureStops));
        header.insert("voxgiToneCurve", Imf::StringAttribute(toneCurveName(image.display.toneCurve)));
    }
    writeFileAtomically(path, [&](const std::string& temporary) {
        Imf::OutputFile file(temporary.c_str(), header);
        file.setFrameBuffer(fb);
        file.writePixels(image.height());
    });
}

Image readExr(const std::string& path) {
    if (!fs::exists(path)) throw InputError(path + ": file not found");
    try {
        Imf::InputFile file(path.c_str());
        Imath::Box2i dw = file.header().dataWindow();
        const std::int64_t width = std::int64_t(dw.max.x) - dw.min.x + 1, height = std::int64_t(dw.max.y) - dw.min.y + 1;
        if (width <= 0 || height <= 0 || width > INT32_MAX || height > INT32_MAX)
            throw InputError(path + ": dataWindow is " + std::to_string(width) + "x" + std::to_string(height) + " pixels");
        // Every channel becomes at most one float per pixel, zeroed first: estimated before
        // allocating (a 1 KB file may claim 2^40 pixels).
        double channels = 0.0;
        for (auto it = file.header().channels().begin(); it != file.header().channels().end(); ++it) channels += 1.0;
        requireMemory(double(width) * double(height) * sizeof(float) * std::max(channels, 1.0),
                      path + ": a " + std::to_string(width) + "x" + std::to_string(height) + " image");
        const int w = int(width), h = int(height);
        Image image(w, h);
        // Group channels into layers: "R","G","B" -> beauty, "a.R" -> a, "Z" -> depth.
        std::map<std::string, std::vector<std::string>> groups;
        for (auto it = file.header().channels().begin(); it != file.header().channels().end(); ++it) {
            std::string name = it.name();
            auto dot = name.rfind('.');
            std::string layer = dot == std::string::npos ? "" : name.substr(0, dot);
            std::string chan = dot == std::string::npos ? name : name.substr(dot + 1);
            if (layer.empty()) layer = (chan == "Z") ? "depth" : "beauty";
            groups[layer].push_back(name);
        }
        Imf::FrameBuffer fb;
        std::vector<std::pair<std::string, std::vector<std::string>>> order(groups.begin(), groups.end());
        for (auto& [layer, names] : order) {
            bool rgb = names.size() >= 3;
            ImageLayer& l = image.layer(layer, rgb ? 3 : 1);
            if (rgb) {
                for (int c = 0; c < 3; ++c) {
                    std::string want = layer == "beauty" ? kRgb[c] : layer + "." + kRgb[c];
                    char* base = reinterpret_cast<char*>(l.data.data()) + std::size_t(c) * sizeof(float) -
                                 (std::ptrdiff_t(dw.min.x) + std::ptrdiff_t(dw.min.y) * w) * 3 * std::ptrdiff_t(sizeof(float));
                    fb.insert(want, Imf::Slice(Imf::FLOAT, base, 3 * sizeof(float), 3 * sizeof(float) * std::size_t(w)));
                }
            } else {
                char* base = reinterpret_cast<char*>(l.data.data()) -
                             (std::ptrdiff_t(dw.min.x) + std::ptrdiff_t(dw.min.y) * w) * std::ptrdiff_t(sizeof(float));
                fb.insert(names.front(), Imf::Slice(Imf::FLOAT, base, sizeof(float), sizeof(float) * std::size_t(w)));
            }
        }
        file.setFrameBuffer(fb);
        file.readPixels(dw.min.y, dw.max.y);
        if (const auto* e = file.header().findTypedAttribute<Imf::FloatAttribute>("voxgiExposureStops")) {
            image.display.set = true;
            image.display.exposureStops = e->value();
            if (const auto* c = file.header().findTypedAttribute<Imf::StringAttribute>("voxgiToneCurve"))
                image.display.toneCurve = std::max(toneCurveFromName(c->value()), 0);
        }
        return image;
    } catch (const InputError&) {
        throw;
    } catch (const std::exception& e) {
        throw InputError(path + ": cannot read EXR (" + e.what() + ")");
    }
}

glm::vec3 toneMapToSrgb(glm::vec3 x, float exposureStops, int toneCurve) {
    for (int c = 0; c < 3; ++c)
        if (!std::isfinite(x[c])) x[c] = 0.0f;
    return shading::displaySrgb(x, std::exp2(exposureStops), toneCurve);
}

float autoExposureStops(const Image& image, const std::string& layer) {
    const ImageLayer* l = image.find(layer);
    if (!l || l->channels != 3) return 0.0f;
    double logSum = 0.0;
    std::size_t lit = 0;
    for (std::size_t i = 0; i + 2 < l->data.size(); i += 3) {
        const float y = shading::luminanceRec709(glm::vec3(l->data[i], l->data[i + 1], l->data[i + 2]));
        if (!(y > 0.0f) || !std::isfinite(y)) continue;
        logSum += std::log(double(y));
        ++lit;
    }
    if (lit == 0) return 0.0f;
    const double stops = std::log2(double(shading::kExposureKey)) - logSum / double(lit) / std::log(2.0);
    return float(std::clamp(stops, -30.0, 30.0));
}

float adaptExposure(float current, float target, float dtSeconds, float tauSeconds) {
    if (!(tauSeconds > 0.0f)) return target;
    return target + (current - target) * std::exp(-std::max(dtSeconds, 0.0f) / tauSeconds);
}

const char* toneCurveName(int toneCurve) { return toneCurve == shading::kToneReinhard ? "reinhard" : "filmic"; }

int toneCurveFromName(const std::string& name) {
    if (name == "filmic") return shading::kToneFilmic;
    if (name == "reinhard") return shading::kToneReinhard;
    return -1;
}

void writePngRgb8(const std::string& path, int width, int height, const std::vector<std::uint8_t>& rgb) {
    writeFileAtomically(path, [&](const std::string& temporary) {
        if (!stbi_write_png(temporary.c_str(), width, height, 3, rgb.data(), width * 3))
            throw std::runtime_error("PNG encoder failed");
    });
}

void writePng(const std::string& path, const Image& image, const std::string& layer, float exposureStops, int toneCurve) {
    if (!image.find(layer)) throw InputError(path + ": image has no layer '" + layer + "'");
    std::vector<std::uint8_t> rgb(image.pixelCount() * 3);
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) {
            glm::vec3 c = toneMapToSrgb(image.rgb(layer, x, y), exposureStops, toneCurve);
            std::size_t i = (std::size_t(y) * std::size_t(image.width()) + std::size_t(x)) * 3;
            for (int k = 0; k < 3; ++k) rgb[i + std::size_t(k)] = std::uint8_t(std::lround(c[k] * 255.0f));
        }
    writePngRgb8(path, image.width(), image.height(), rgb);
}

}  // namespace voxgi
