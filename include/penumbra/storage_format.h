// Storage formats of encoded channels, their sizes, and the rounding each applies, so the CPU
// reference sees the values the GPU textures hold.
#pragma once

#include <string_view>

#include "penumbra/technique.h"

namespace penumbra {

enum class StorageFormat { Float32, Float16, Unorm16, Unorm8 };

std::string_view storageFormatName(StorageFormat format);  // "float32", "float16", ...
int bytesPerChannel(StorageFormat format);
// The format a technique's channels are stored in under its params.
StorageFormat techniqueStorage(Technique technique, const TechniqueParams& params);
// How a device rounds floats it stores as fp16. GL allows either; Mesa's llvmpipe truncates in
// shader image stores, vendor GPUs round to nearest (gl::Renderer::halfFloatRounding measures it).
enum class HalfRounding { Nearest, TowardZero };

// The value the format holds for v: fp16 rounding, unorm clamping and rounding, fp32 as is.
float quantizeToStorage(float v, StorageFormat format,
                        HalfRounding halfRounding = HalfRounding::Nearest);

}  // namespace penumbra
