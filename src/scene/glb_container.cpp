// The binary glTF container's header and chunks (glTF 2.0 §4.4), bounds first.
#include "glb_container.h"

#include <cstring>

#include "penumbra/error.h"

namespace penumbra::scene {
namespace {

constexpr uint32_t kJsonChunk = 0x4E4F534Au;  // "JSON", little-endian
constexpr uint32_t kBinChunk = 0x004E4942u;   // "BIN\0"
constexpr size_t kHeaderBytes = 12;
constexpr size_t kChunkHeaderBytes = 8;

uint32_t readUint32(std::span<const uint8_t> bytes, size_t at) {
  const uint8_t* p = bytes.data() + at;
  return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}

std::string at(size_t offset) {
  return ", at byte " + std::to_string(offset);
}

}  // namespace

bool isGlb(std::span<const uint8_t> bytes) {
  return bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
}

std::span<const uint8_t> glbJsonChunk(std::span<const uint8_t> bytes, const std::string& name) {
  if (bytes.size() < kHeaderBytes + kChunkHeaderBytes) {
    throw Error(name + ": a binary glTF of " + std::to_string(bytes.size()) +
                " bytes is shorter than its 12-byte header and the JSON chunk's 8-byte header");
  }
  if (const uint32_t version = readUint32(bytes, 4); version != 2) {
    throw Error(name + ": binary glTF version " + std::to_string(version) +
                "; only version 2 is read" + at(4));
  }
  // The container ends where the header says; bytes after it are not part of the glTF.
  const size_t length = readUint32(bytes, 8);
  if (length > bytes.size()) {
    throw Error(name + ": the binary glTF header gives a length of " + std::to_string(length) +
                " bytes, but the file holds " + std::to_string(bytes.size()) + at(8));
  }
  size_t offset = kHeaderBytes;
  std::span<const uint8_t> json;
  for (int chunk = 0; offset < length; ++chunk) {
    if (length - offset < kChunkHeaderBytes) {
      throw Error(name + ": a chunk header needs 8 bytes, but " + std::to_string(length - offset) +
                  " are left of the length the binary glTF header gives" + at(offset));
    }
    const size_t size = readUint32(bytes, offset);
    const uint32_t type = readUint32(bytes, offset + 4);
    const size_t data = offset + kChunkHeaderBytes;
    if (size > length - data) {
      throw Error(name + ": chunk " + std::to_string(chunk) + " gives " + std::to_string(size) +
                  " bytes of data, but " + std::to_string(length - data) +
                  " are left of the length the binary glTF header gives" + at(offset));
    }
    if (chunk == 0) {
      if (type != kJsonChunk) {
        throw Error(name + ": the first chunk of a binary glTF must be its JSON" + at(offset + 4));
      }
      json = bytes.subspan(data, size);
    } else if (chunk == 1 && type != kBinChunk) {
      // Later chunks of unknown types are skipped (§4.4.3); the second, if any, holds the buffer.
      throw Error(name + ": the second chunk of a binary glTF must be its BIN buffer" +
                  at(offset + 4));
    }
    offset = data + size;
  }
  if (json.empty()) throw Error(name + ": a binary glTF with no JSON chunk data" + at(12));
  return json;
}

}  // namespace penumbra::scene
