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
  return " (at byte " + std::to_string(offset) + ")";
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
    throw Error(name + ": binary glTF version " + std::to_string(version) + at(4) +
                "; only version 2 is read");
  }
  // The container ends where the header says; bytes after it are not part of the glTF.
  const size_t length = readUint32(bytes, 8);
  if (length > bytes.size()) {
    throw Error(name + ": the binary glTF header gives a length of " + std::to_string(length) +
                " bytes" + at(8) + ", but the file holds " + std::to_string(bytes.size()));
  }
  if (length < kHeaderBytes + kChunkHeaderBytes) {
    throw Error(name + ": the binary glTF header gives a length of " + std::to_string(length) +
                " bytes" + at(8) + ", too short for the JSON chunk that must follow it");
  }
  size_t offset = kHeaderBytes;
  std::span<const uint8_t> json;
  for (int chunk = 0; offset < length; ++chunk) {
    if (length - offset < kChunkHeaderBytes) {
      throw Error(name + ": chunk " + std::to_string(chunk) + "'s header" + at(offset) +
                  " needs 8 bytes, but " + std::to_string(length - offset) +
                  " are left of the length the binary glTF header gives");
    }
    const size_t size = readUint32(bytes, offset);
    const uint32_t type = readUint32(bytes, offset + 4);
    const size_t data = offset + kChunkHeaderBytes;
    if (size > length - data) {
      throw Error(name + ": chunk " + std::to_string(chunk) + at(offset) + " gives " +
                  std::to_string(size) + " bytes of data, but " + std::to_string(length - data) +
                  " are left of the length the binary glTF header gives");
    }
    if (chunk == 0) {
      if (type != kJsonChunk) {
        throw Error(name + ": chunk 0" + at(offset) +
                    " is not JSON; a binary glTF starts with its JSON chunk");
      }
      if (size == 0) throw Error(name + ": the JSON chunk" + at(offset) + " is empty");
      json = bytes.subspan(data, size);
    } else if (chunk == 1 && type != kBinChunk) {
      // The specification has readers skip chunks of unknown types; tinygltf, which reads the
      // buffer, takes the second chunk for the BIN chunk whatever its type.
      throw Error(name + ": chunk 1" + at(offset) +
                  " is not BIN; the second chunk of a binary glTF must hold its buffer here");
    }
    offset = data + size;
  }
  return json;
}

}  // namespace penumbra::scene
