// Rounding to storage, as the device rounds: unorm codes to nearest with ties to even (the
// device's colour-output conversion; a mip level's mean of four texels weighted 1/4 lands on
// ties), halves to nearest or toward zero as the device's image stores do.
#include <gtest/gtest.h>

#include <cmath>

#include "penumbra/storage_format.h"

namespace penumbra {
namespace {

// Every float whose code-space product is exactly k + 1/2 rounds to the even one of k, k + 1.
void expectTiesToEven(StorageFormat format, int maxCode) {
  const float scale = float(maxCode);
  int ties = 0;
  for (int k = 0; k < maxCode; ++k) {
    const float v = (float(k) + 0.5f) / scale;
    if (v * scale != float(k) + 0.5f) continue;  // not a tie in float arithmetic
    ++ties;
    const int even = k % 2 == 0 ? k : k + 1;
    const float code = quantizeToStorage(v, format) * scale;
    ASSERT_EQ(std::nearbyint(code), float(even)) << "k " << k;
  }
  EXPECT_GT(ties, maxCode / 4) << "too few ties to tell the rule";
}

TEST(StorageFormat, UnormRoundsTiesToEven) {
  expectTiesToEven(StorageFormat::Unorm8, 255);
  expectTiesToEven(StorageFormat::Unorm16, 65535);
}

TEST(StorageFormat, UnormRoundsToTheNearestCodeAwayFromTies) {
  EXPECT_EQ(quantizeToStorage(10.4f / 255.0f, StorageFormat::Unorm8) * 255.0f, 10.0f);
  EXPECT_EQ(quantizeToStorage(10.6f / 255.0f, StorageFormat::Unorm8) * 255.0f, 11.0f);
  // Out of range clamps (CSM's basis relies on it: shared/csm.h).
  EXPECT_EQ(quantizeToStorage(-0.5f, StorageFormat::Unorm8), 0.0f);
  EXPECT_EQ(quantizeToStorage(1.5f, StorageFormat::Unorm8), 1.0f);
  EXPECT_EQ(quantizeToStorage(-0.5f, StorageFormat::Unorm16), 0.0f);
  EXPECT_EQ(quantizeToStorage(1.5f, StorageFormat::Unorm16), 1.0f);
}

TEST(StorageFormat, HalvesRoundToNearestOrTowardZeroAsTheDeviceDoes) {
  // 1 + 3/4 of a half's step (2^-10 near 1): nearest goes up, toward zero goes down; negative
  // values mirror.
  const float step = 1.0f / 1024.0f;
  const float v = 1.0f + 0.75f * step;
  EXPECT_EQ(quantizeToStorage(v, StorageFormat::Float16, HalfRounding::Nearest), 1.0f + step);
  EXPECT_EQ(quantizeToStorage(v, StorageFormat::Float16, HalfRounding::TowardZero), 1.0f);
  EXPECT_EQ(quantizeToStorage(-v, StorageFormat::Float16, HalfRounding::TowardZero), -1.0f);
  EXPECT_EQ(quantizeToStorage(v, StorageFormat::Float32), v);
}

}  // namespace
}  // namespace penumbra
