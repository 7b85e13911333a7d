// Storage format sizes and rounding.
#include "penumbra/storage_format.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/packing.hpp>

namespace penumbra {

static_assert(shaders::kStorageFloat32 == int(StorageFormat::Float32));
static_assert(shaders::kStorageFloat16 == int(StorageFormat::Float16));
static_assert(shaders::kStorageUnorm16 == int(StorageFormat::Unorm16));
static_assert(shaders::kStorageUnorm8 == int(StorageFormat::Unorm8));

std::string_view storageFormatName(StorageFormat format) {
  switch (format) {
    case StorageFormat::Float32: return "float32";
    case StorageFormat::Float16: return "float16";
    case StorageFormat::Unorm16: return "unorm16";
    case StorageFormat::Unorm8: return "unorm8";
  }
  return "unknown";
}

int bytesPerChannel(StorageFormat format) {
  switch (format) {
    case StorageFormat::Float32: return 4;
    case StorageFormat::Float16: return 2;
    case StorageFormat::Unorm16: return 2;
    case StorageFormat::Unorm8: return 1;
  }
  return 4;
}

StorageFormat techniqueStorage(Technique technique, const TechniqueParams& params) {
  checkTechnique(technique);
  switch (technique) {
    case Technique::Vsm: return StorageFormat(params.vsm.storage);
    case Technique::Lvsm: return StorageFormat(params.lvsm.storage);
    case Technique::Evsm2:
    case Technique::Evsm4: return StorageFormat(params.evsm.storage);
    case Technique::Csm: return StorageFormat(params.csm.storage);
    case Technique::PowerCdf: return StorageFormat(params.powerCdf.storage);
    case Technique::Msm: return StorageFormat(params.msm.storage);
    case Technique::Hard:
    case Technique::Pcf:
    case Technique::Esm: return StorageFormat::Float32;
  }
  return StorageFormat::Float32;
}

namespace {

// fp16 rounded toward zero: the nearest half, one step closer to zero when it lies beyond v.
// Halves are sign and magnitude, so a step toward zero is one less in the 16-bit pattern.
float halfTowardZero(float v) {
  glm::uint16 bits = glm::packHalf1x16(v);
  const float nearest = glm::unpackHalf1x16(bits);
  if (std::isnan(v)) return nearest;
  if (std::abs(nearest) > std::abs(v) && (bits & 0x7fffu) != 0) --bits;
  return glm::unpackHalf1x16(bits);
}

}  // namespace

float quantizeToStorage(float v, StorageFormat format, HalfRounding halfRounding) {
  switch (format) {
    case StorageFormat::Float32: return v;
    case StorageFormat::Float16:
      if (halfRounding == HalfRounding::TowardZero) return halfTowardZero(v);
      return glm::unpackHalf1x16(glm::packHalf1x16(v));
    // Nearest, ties to even: IEEE's default, and how llvmpipe converts colour outputs (GL leaves
    // ties to the implementation). A mip level's mean of four codes often lands on a tie.
    case StorageFormat::Unorm16:
      return std::nearbyint(std::clamp(v, 0.0f, 1.0f) * 65535.0f) / 65535.0f;
    case StorageFormat::Unorm8: return std::nearbyint(std::clamp(v, 0.0f, 1.0f) * 255.0f) / 255.0f;
  }
  return v;
}

}  // namespace penumbra
