// Generated scene files for the loader, command-line and rendering tests: glTF 2.0 JSON with its
// buffer embedded as a base64 data URI, grids, PNG headers; and a guard for FIFO tests.
#pragma once

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <glm/glm.hpp>
#include <string>
#include <thread>
#include <vector>

namespace penumbra::testing {

inline std::string base64(const std::vector<uint8_t>& bytes) {
  static const char* kDigits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    uint32_t n = uint32_t(bytes[i]) << 16;
    if (i + 1 < bytes.size()) n |= uint32_t(bytes[i + 1]) << 8;
    if (i + 2 < bytes.size()) n |= bytes[i + 2];
    out += kDigits[(n >> 18) & 63];
    out += kDigits[(n >> 12) & 63];
    out += i + 1 < bytes.size() ? kDigits[(n >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? kDigits[n & 63] : '=';
  }
  return out;
}

// One mesh of triangles (positions, 16-bit indices) and the "nodes"/"scenes" JSON given;
// `primitiveMembers` and `topMembers` are added to its primitive and to the document
// (",\"material\":0", ",\"images\":[...]").
inline std::string gltfWithMesh(const std::vector<glm::vec3>& positions,
                                const std::vector<uint16_t>& indices, const std::string& nodes,
                                const std::string& sceneRoots,
                                const std::string& primitiveMembers = "",
                                const std::string& topMembers = "") {
  std::vector<uint8_t> buffer(positions.size() * 12 + indices.size() * 2);
  std::memcpy(buffer.data(), positions.data(), positions.size() * 12);
  std::memcpy(buffer.data() + positions.size() * 12, indices.data(), indices.size() * 2);
  glm::vec3 lo(1e30f), hi(-1e30f);
  for (glm::vec3 p : positions) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  const auto vec = [](glm::vec3 v) {
    return "[" + std::to_string(v.x) + "," + std::to_string(v.y) + "," + std::to_string(v.z) + "]";
  };
  return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":)" + sceneRoots +
         R"(}],"nodes":)" + nodes +
         R"(,"meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1)" +
         primitiveMembers + R"(}]}],"buffers":[{"byteLength":)" + std::to_string(buffer.size()) +
         R"(,"uri":"data:application/octet-stream;base64,)" + base64(buffer) + R"("}],)" +
         R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":)" +
         std::to_string(positions.size() * 12) + R"(},{"buffer":0,"byteOffset":)" +
         std::to_string(positions.size() * 12) + R"(,"byteLength":)" +
         std::to_string(indices.size() * 2) + R"(}],)" +
         R"("accessors":[{"bufferView":0,"componentType":5126,"count":)" +
         std::to_string(positions.size()) + R"(,"type":"VEC3","min":)" + vec(lo) + R"(,"max":)" +
         vec(hi) + R"(},{"bufferView":1,"componentType":5123,"count":)" +
         std::to_string(indices.size()) + R"(,"type":"SCALAR"}])" + topMembers + "}";
}

// A side x side grid of vertices in the xz plane, two triangles per cell (side <= 256: 16-bit
// indices).
struct Grid {
  std::vector<glm::vec3> positions;
  std::vector<uint16_t> indices;
};
inline Grid grid(int side) {
  Grid g;
  for (int z = 0; z < side; ++z) {
    for (int x = 0; x < side; ++x) g.positions.emplace_back(float(x), 0.0f, float(z));
  }
  for (int z = 0; z + 1 < side; ++z) {
    for (int x = 0; x + 1 < side; ++x) {
      const auto a = uint16_t(z * side + x), b = uint16_t(a + side);
      g.indices.insert(g.indices.end(),
                       {a, b, uint16_t(a + 1), uint16_t(a + 1), b, uint16_t(b + 1)});
    }
  }
  return g;
}

// A PNG's signature and header chunk declaring width x height RGB8, and no image data: its size
// reads from the header, decoding it fails.
inline std::string pngHeaderOnly(uint32_t width, uint32_t height) {
  const auto bigEndian = [](uint32_t v) {
    return std::string{char(v >> 24), char(v >> 16), char(v >> 8), char(v)};
  };
  return std::string("\x89PNG\r\n\x1a\n", 8) + bigEndian(13) + "IHDR" + bigEndian(width) +
         bigEndian(height) + std::string("\x08\x02\x00\x00\x00", 5) + bigEndian(0);
}

// Opens the FIFO's other end after five seconds, should a reader be blocked on it: a loader
// that opens it blocking then reads an empty file and its test fails instead of hanging (ctest's
// TIMEOUT is the last resort).
class FifoUnblocker {
 public:
  explicit FifoUnblocker(std::filesystem::path fifo)
      : thread_([this, fifo = std::move(fifo)] {
          const auto start = std::chrono::steady_clock::now();
          while (!done_) {
            if (std::chrono::steady_clock::now() - start > std::chrono::seconds(5)) {
              const int fd = open(fifo.c_str(), O_WRONLY | O_NONBLOCK);
              if (fd >= 0) close(fd);
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(50));
          }
        }) {}
  ~FifoUnblocker() {
    done_ = true;
    thread_.join();
  }
  FifoUnblocker(const FifoUnblocker&) = delete;
  FifoUnblocker& operator=(const FifoUnblocker&) = delete;

 private:
  std::atomic<bool> done_{false};
  std::thread thread_;
};

inline std::filesystem::path writeFile(const std::filesystem::path& path, const std::string& text) {
  std::filesystem::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

}  // namespace penumbra::testing
