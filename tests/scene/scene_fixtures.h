// Generated scene files for the loader and rendering tests: glTF 2.0 JSON with its buffer
// embedded as a base64 data URI, written into the test's build folder.
#pragma once

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <glm/glm.hpp>
#include <string>
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

// One mesh of triangles (positions, 16-bit indices) and the "nodes"/"scenes" JSON given.
inline std::string gltfWithMesh(const std::vector<glm::vec3>& positions,
                                const std::vector<uint16_t>& indices, const std::string& nodes,
                                const std::string& sceneRoots) {
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
         R"(,"meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],)" +
         R"("buffers":[{"byteLength":)" + std::to_string(buffer.size()) +
         R"(,"uri":"data:application/octet-stream;base64,)" + base64(buffer) + R"("}],)" +
         R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":)" +
         std::to_string(positions.size() * 12) + R"(},{"buffer":0,"byteOffset":)" +
         std::to_string(positions.size() * 12) + R"(,"byteLength":)" +
         std::to_string(indices.size() * 2) + R"(}],)" +
         R"("accessors":[{"bufferView":0,"componentType":5126,"count":)" +
         std::to_string(positions.size()) + R"(,"type":"VEC3","min":)" + vec(lo) + R"(,"max":)" +
         vec(hi) + R"(},{"bufferView":1,"componentType":5123,"count":)" +
         std::to_string(indices.size()) + R"(,"type":"SCALAR"}]})";
}

inline std::filesystem::path writeFile(const std::filesystem::path& path, const std::string& text) {
  std::filesystem::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

}  // namespace penumbra::testing
