// A texture whose compressed data expands far beyond its declared size (a PNG declaring 1x1
// whose zlib stream inflates to 64 MiB, from 64 KiB) is refused while it decodes: stb_image's
// allocations are held to what the declared size can need, so the memory budget charged from the
// header holds. The same stream with the size it truly has decodes.
#include <gtest/gtest.h>
#include <zlib.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "penumbra/scene.h"

namespace penumbra {
namespace {

namespace fs = std::filesystem;

void appendBigEndian(std::string& out, uint32_t value) {
  for (int shift = 24; shift >= 0; shift -= 8) out += char((value >> shift) & 0xff);
}

void appendChunk(std::string& out, const char* type, const std::string& data) {
  appendBigEndian(out, uint32_t(data.size()));
  const std::string typed = std::string(type, 4) + data;
  out += typed;
  appendBigEndian(
      out, uint32_t(crc32(0, reinterpret_cast<const Bytef*>(typed.data()), uInt(typed.size()))));
}

// An 8-bit RGBA PNG declaring width x height whose image data inflates to `rawBytes` zero bytes.
std::string png(uint32_t width, uint32_t height, size_t rawBytes) {
  std::string out("\x89PNG\r\n\x1a\n", 8);
  std::string header;
  appendBigEndian(header, width);
  appendBigEndian(header, height);
  header +=
      std::string("\x08\x06\x00\x00\x00", 5);  // 8 bits, RGBA, deflate, filter 0, no interlace
  appendChunk(out, "IHDR", header);
  const std::vector<Bytef> raw(rawBytes, 0);
  uLongf packedSize = compressBound(uLong(raw.size()));
  std::vector<Bytef> packed(packedSize);
  compress2(packed.data(), &packedSize, raw.data(), uLong(raw.size()), 9);
  appendChunk(out, "IDAT", std::string(reinterpret_cast<const char*>(packed.data()), packedSize));
  appendChunk(out, "IEND", "");
  return out;
}

Scene loadTexturedTriangle(const std::string& name, const std::string& pngBytes) {
  const fs::path dir = fs::temp_directory_path() / ("penumbra-image-bomb-" + name);
  fs::create_directories(dir);
  std::ofstream(dir / "t.png", std::ios::binary) << pngBytes;
  std::ofstream(dir / "t.mtl") << "newmtl m\nmap_Kd t.png\n";
  std::ofstream(dir / "t.obj") << "mtllib t.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\n"
                                  "vt 0 1\nusemtl m\nf 1/1 2/2 3/3\n";
  SceneLoadOptions options;
  options.maxMemoryBytes = 256u << 20;
  Scene scene = loadScene((dir / "t.obj").string(), options);
  fs::remove_all(dir);
  return scene;
}

TEST(ImageBomb, ADeclaredOneByOnePngThatInflatesTo64MiBIsRefusedWhileDecoding) {
  const std::string bomb = png(1, 1, size_t(64) << 20);
  ASSERT_LT(bomb.size(), size_t(256) << 10);  // what makes it a bomb: a small file
  const Scene scene = loadTexturedTriangle("bomb", bomb);
  EXPECT_TRUE(scene.textures.empty());
  ASSERT_EQ(scene.warnings.size(), 1u);
  EXPECT_NE(scene.warnings[0].find("decompression bomb"), std::string::npos) << scene.warnings[0];
}

TEST(ImageBomb, TheSameDataWithItsTrueSizeDecodes) {
  // 2048 rows of a filter byte and 2048 RGBA texels: 16 MiB + 2 KiB, as the header says.
  const Scene scene = loadTexturedTriangle("honest", png(2048, 2048, 2048 * (1 + 2048 * 4)));
  EXPECT_TRUE(scene.warnings.empty()) << scene.warnings.front();
  ASSERT_EQ(scene.textures.size(), 1u);
  EXPECT_EQ(scene.textures[0].width, 2048);
}

}  // namespace
}  // namespace penumbra
