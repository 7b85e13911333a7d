// PNG (libpng) and OpenEXR (OpenEXR) reading and writing.
#include "penumbra/image_io.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <png.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <cstring>
#include <memory>
#include <vector>

#include "penumbra/diagnostic_images.h"
#include "penumbra/error.h"
#include "penumbra/output_journal.h"
#include "penumbra/srgb.h"

namespace penumbra {
namespace {

using FilePtr = std::unique_ptr<FILE, int (*)(FILE*)>;

FilePtr open(const std::filesystem::path& path, const char* mode) {
  if (mode[0] == 'w') recordOutput(path);
  FilePtr file(std::fopen(path.c_str(), mode), &std::fclose);
  if (!file) throw Error("cannot open " + path.string() + (mode[0] == 'w' ? " for writing" : ""));
  return file;
}

void writePng(const std::filesystem::path& path, int width, int height, int colorType, int bitDepth,
              const std::vector<png_bytep>& rows, bool srgb) {
  FilePtr file = open(path, "wb");
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!png || !info) throw Error("libpng could not start writing " + path.string());
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    throw Error("libpng failed while writing " + path.string());
  }
  png_init_io(png, file.get());
  png_set_IHDR(png, info, png_uint_32(width), png_uint_32(height), bitDepth, colorType,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  // The sRGB chunk (with its gAMA and cHRM fallbacks) tells viewers what the samples mean.
  if (srgb) png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
  png_write_info(png, info);
  if (bitDepth == 16) png_set_swap(png);  // our samples are little-endian in memory
  png_write_image(png, const_cast<png_bytepp>(rows.data()));
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
}

}  // namespace

void requireFinite(const Image& image, std::string_view what) {
  const auto data = image.data();
  for (size_t i = 0; i < data.size(); ++i) {
    if (!std::isfinite(data[i])) {
      const size_t texel = i / size_t(image.channels());
      throw Error(std::string(what) + " holds a non-finite value at (" +
                  std::to_string(texel % size_t(image.width())) + ", " +
                  std::to_string(texel / size_t(image.width())) + "); refusing to write it");
    }
  }
}

std::vector<uint8_t> encodeSrgb8(const Image& image) {
  if (image.channels() < 3) throw Error("a colour image needs 3 or 4 channels");
  std::vector<uint8_t> pixels(size_t(image.width()) * size_t(image.height()) * 3);
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) {
      for (int c = 0; c < 3; ++c) {
        const float encoded = srgbFromLinear(image.at(x, y, c));
        pixels[(size_t(y) * size_t(image.width()) + size_t(x)) * 3 + size_t(c)] =
            uint8_t(std::lround(encoded * 255.0f));
      }
    }
  }
  return pixels;
}

void writeEncodedColorPng(int width, int height, std::span<const uint8_t> rgb,
                          const std::filesystem::path& path) {
  if (width < 1 || height < 1 || rgb.size() != size_t(width) * size_t(height) * 3) {
    throw Error("cannot write " + path.string() + ": " + std::to_string(rgb.size()) +
                " bytes are not a " + std::to_string(width) + "x" + std::to_string(height) +
                " RGB image");
  }
  std::vector<png_bytep> rows;
  for (int y = 0; y < height; ++y) {
    rows.push_back(const_cast<png_bytep>(&rgb[size_t(y) * size_t(width) * 3]));
  }
  writePng(path, width, height, PNG_COLOR_TYPE_RGB, 8, rows, true);
}

void writeColorPng(const Image& image, const std::filesystem::path& path) {
  if (image.channels() < 3) throw Error("a colour PNG needs 3 or 4 channels");
  requireFinite(image, path.string());
  const std::vector<uint8_t> pixels = encodeSrgb8(image);
  writeEncodedColorPng(image.width(), image.height(), pixels, path);
}

void writeGrey16Png(const Image& image, const std::filesystem::path& path) {
  if (image.channels() != 1) throw Error("a grey PNG needs one channel");
  requireFinite(image, path.string());
  std::vector<uint16_t> pixels(size_t(image.width()) * size_t(image.height()));
  for (size_t i = 0; i < pixels.size(); ++i) {
    pixels[i] = uint16_t(std::lround(std::clamp(image.data()[i], 0.0f, 1.0f) * 65535.0f));
  }
  std::vector<png_bytep> rows;
  for (int y = 0; y < image.height(); ++y) {
    rows.push_back(reinterpret_cast<png_bytep>(&pixels[size_t(y) * size_t(image.width())]));
  }
  writePng(path, image.width(), image.height(), PNG_COLOR_TYPE_GRAY, 16, rows, false);
}

void writeFailureMaskPng(const Image& diagnostic, const Image& color,
                         const std::filesystem::path& path) {
  writeColorPng(failureMaskImage(diagnostic, color), path);
}

void writeLayerIndexPng(const Image& diagnostic, const Image& color,
                        const std::filesystem::path& path) {
  writeColorPng(layerIndexImage(diagnostic, color), path);
}

namespace {

// Reads a PNG that must be of `colorType` with `bitDepth` bits per sample (`expected` names it in
// the error otherwise) into an image of the samples divided by their maximum, row 0 at the top.
Image readPng(const std::filesystem::path& path, int colorType, int bitDepth, int channels,
              const char* expected) {
  FilePtr file = open(path, "rb");
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!png || !info) throw Error("libpng could not start reading " + path.string());
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    throw Error(path.string() + " is not a readable PNG");
  }
  png_init_io(png, file.get());
  png_read_info(png, info);
  const int width = int(png_get_image_width(png, info));
  const int height = int(png_get_image_height(png, info));
  if (png_get_color_type(png, info) != colorType || png_get_bit_depth(png, info) != bitDepth) {
    png_destroy_read_struct(&png, &info, nullptr);
    throw Error(path.string() + " is not " + expected);
  }
  if (bitDepth == 16) png_set_swap(png);  // PNG stores big-endian samples
  const size_t bytes = size_t(bitDepth / 8);
  const size_t rowBytes = size_t(width) * size_t(channels) * bytes;
  std::vector<uint8_t> pixels(rowBytes * size_t(height));
  std::vector<png_bytep> rows;
  for (int y = 0; y < height; ++y) rows.push_back(&pixels[size_t(y) * rowBytes]);
  png_read_image(png, rows.data());
  png_destroy_read_struct(&png, &info, nullptr);
  Image image(width, height, channels);
  const float maximum = float((1 << bitDepth) - 1);
  for (size_t i = 0; i < image.data().size(); ++i) {
    uint16_t sample = pixels[i * bytes];
    if (bytes == 2) std::memcpy(&sample, &pixels[i * 2], 2);
    image.data()[i] = float(sample) / maximum;
  }
  return image;
}

}  // namespace

Image readGrey16Png(const std::filesystem::path& path) {
  return readPng(path, PNG_COLOR_TYPE_GRAY, 16, 1, "a 16-bit greyscale PNG");
}

Image readEncodedColorPng(const std::filesystem::path& path) {
  return readPng(path, PNG_COLOR_TYPE_RGB, 8, 3, "an 8-bit RGB PNG");
}

void writeFloatExr(const Image& image, const std::filesystem::path& path) {
  if (image.channels() != 1) throw Error("a float EXR here holds one channel");
  requireFinite(image, path.string());
  try {
    Imf::Header header(image.width(), image.height());
    header.channels().insert("Y", Imf::Channel(Imf::FLOAT));
    recordOutput(path);
    Imf::OutputFile file(path.c_str(), header);
    Imf::FrameBuffer frame;
    frame.insert("Y",
                 Imf::Slice(Imf::FLOAT,
                            const_cast<char*>(reinterpret_cast<const char*>(image.data().data())),
                            sizeof(float), sizeof(float) * size_t(image.width())));
    file.setFrameBuffer(frame);
    file.writePixels(image.height());
  } catch (const std::exception& e) {
    throw Error("writing " + path.string() + " failed: " + e.what());
  }
}

Image readFloatExr(const std::filesystem::path& path) {
  try {
    Imf::InputFile file(path.c_str());
    const Imath::Box2i window = file.header().dataWindow();
    const int width = window.max.x - window.min.x + 1;
    const int height = window.max.y - window.min.y + 1;
    Image image(width, height, 1);
    Imf::FrameBuffer frame;
    char* base = reinterpret_cast<char*>(image.data().data()) -
                 (size_t(window.min.x) + size_t(window.min.y) * size_t(width)) * sizeof(float);
    frame.insert("Y", Imf::Slice(Imf::FLOAT, base, sizeof(float), sizeof(float) * size_t(width)));
    file.setFrameBuffer(frame);
    file.readPixels(window.min.y, window.max.y);
    return image;
  } catch (const std::exception& e) {
    throw Error("reading " + path.string() + " failed: " + e.what());
  }
}

}  // namespace penumbra
