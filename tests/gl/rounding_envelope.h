// The GPU-versus-CPU-twin comparison's tolerance (lookup and soft-shadow parity tests): the
// visibilities the twin reconstructs from its own filtered channels moved by the storage's and
// the sums' rounding.
#pragma once

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "penumbra/filter_mode.h"
#include "penumbra/shadow_lookup.h"
#include "penumbra/storage_format.h"
#include "penumbra/technique.h"

namespace penumbra::testing {

// How far the GPU's filtered channels may lie from the CPU twin's. A pixel is held to the
// visibilities the CPU reconstructs from its own filtered channels each moved by up to that much
// (its rounding envelope), plus kArithmetic, on every pixel: the reconstruction amplifies a
// channel's rounding by its slope, which reaches 1e4 where a Chebyshev or Hamburger bound sits
// at its variance floor and is 0 on flat ground, so no single visibility tolerance is both
// strict and true.
//
// Storage: both sides encode in fp32 (the GPU with fused multiply-adds) and round to the same
// format, so a value within an ulp of a rounding boundary of the format may be stored one step
// apart: unorm16 1/65535 and unorm8 1/255 absolute, fp16 one ulp near the value (2^-10 relative
// at most: 10 fraction bits), fp32 one ulp. Blends, mip levels and box sums are convex
// combinations of such texels, so the filtered value keeps that bound.
// Filtering: each side sums n positive terms in fp32 in its own order, each within
// gamma_n ~ n ulps of the exact sum (Higham, Accuracy and Stability of Numerical Algorithms,
// §3.1): n <= 8 texels for point (one), bilinear and trilinear lookups (the texture unit blends
// in fp32 on llvmpipe) and for the summed-area table's four exact 64-bit fixed-point corners
// converted once; anisotropic lookups sum up to 16 trilinear probes, n <= 128.
inline constexpr float kFp32Ulp = 0x1.0p-24f;
// The reconstruction's own fp32 arithmetic in another order (fused multiply-adds on the GPU,
// llvmpipe's exp and log within a few ulps): a few ulps of a visibility <= 1, and of the
// exponent c z of ESM/EVSM (c <= 88: 88 x 2^-24 ~ 5e-6 relative).
inline constexpr float kArithmetic = 1e-5f;

// How far the two sides' receiver-plane depths may differ by rounding (fused multiply-adds on
// the GPU): about 16 ulps of a depth near 1.
inline constexpr float kTieRounding = 1e-6f;

struct ChannelRounding {
  float relative;
  float absolute;
};

inline ChannelRounding channelRounding(FilterMode filter, StorageFormat storage) {
  const float terms = filter == FilterMode::Anisotropic ? 128.0f : 8.0f;
  const float sums = 2.0f * terms * kFp32Ulp;  // both sides' sums, in their own orders
  switch (storage) {
    case StorageFormat::Float32: return {sums + kFp32Ulp, 0.0f};
    case StorageFormat::Float16: return {sums + 0x1.0p-10f, 0.0f};
    case StorageFormat::Unorm16: return {sums, 1.0f / 65535.0f};
    case StorageFormat::Unorm8: return {sums, 1.0f / 255.0f};
  }
  return {sums, 0.0f};
}

struct Envelope {
  float lo;
  float hi;
};

// The visibilities the CPU reconstructs from its filtered channels each moved by up to the
// rounding: every corner of the box for up to six channels; beyond that (CSM's 16, the power
// CDF's 48) every channel alone either way, all together either way, the two corners of the
// local slope, and 64 random corners.
inline Envelope roundingEnvelope(Technique technique, const CpuShadowLookup& twin,
                                 const TechniqueParams& params, const LookupPixel& pixel,
                                 ChannelRounding rounding) {
  const std::vector<float> filtered = twin.filteredChannels(pixel);
  const float receiver = std::clamp(pixel.receiverDepth, 0.0f, 1.0f);
  Envelope e{1.0f, 0.0f};
  auto visit = [&](const std::vector<float>& direction) {
    std::vector<float> moved = filtered;
    for (size_t c = 0; c < moved.size(); ++c) {
      moved[c] += direction[c] * (rounding.relative * std::abs(moved[c]) + rounding.absolute);
    }
    const float v = reconstructVisibility(technique, params, moved, receiver);
    e.lo = std::min(e.lo, v);
    e.hi = std::max(e.hi, v);
  };
  const size_t n = filtered.size();
  if (n <= 6) {
    int corners = 1;
    for (size_t c = 0; c < n; ++c) corners *= 3;
    for (int corner = 0; corner < corners; ++corner) {
      std::vector<float> direction(n);
      int step = corner;
      for (float& d : direction) {
        d = float(step % 3 - 1);
        step /= 3;
      }
      visit(direction);
    }
    return e;
  }
  visit(std::vector<float>(n, 0.0f));
  std::vector<float> slope(n, 0.0f);  // the sign of each channel's effect on visibility
  for (float sign : {-1.0f, 1.0f}) {
    visit(std::vector<float>(n, sign));
    for (size_t c = 0; c < n; ++c) {
      std::vector<float> direction(n, 0.0f);
      direction[c] = sign;
      const Envelope before = e;
      e = {1.0f, 0.0f};
      visit(direction);
      slope[c] += sign * (e.hi + e.lo) * 0.5f;
      e = {std::min(e.lo, before.lo), std::max(e.hi, before.hi)};
    }
  }
  // The corners the local slope points to: exact for CSM's series, linear in its channels.
  for (float sign : {-1.0f, 1.0f}) {
    std::vector<float> direction(n);
    for (size_t c = 0; c < n; ++c) direction[c] = slope[c] > 0.0f ? sign : -sign;
    visit(direction);
  }
  std::mt19937 rng(9);
  for (int trial = 0; trial < 64; ++trial) {
    std::vector<float> direction(n);
    for (float& d : direction) d = (rng() & 1u) ? 1.0f : -1.0f;
    visit(direction);
  }
  return e;
}

}  // namespace penumbra::testing
