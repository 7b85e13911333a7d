// Error metrics on synthetic images with known answers.
#include <gtest/gtest.h>

#include <cmath>

#include "penumbra/error.h"
#include "penumbra/metrics.h"

namespace penumbra {
namespace {

Image filled(int w, int h, float v) {
  return Image(w, h, 1, v);
}

TEST(Metrics, KnownErrorsOfAConstantOffset) {
  const Image reference = filled(10, 10, 0.5f);
  const Image estimate = filled(10, 10, 0.6f);
  const Image mask = filled(10, 10, 1.0f);
  const VisibilityErrors e = measureVisibilityErrors(estimate, reference, mask, 0.05);
  EXPECT_EQ(e.pixels, 100);
  EXPECT_NEAR(e.rmse, 0.1, 1e-6);
  EXPECT_NEAR(e.meanAbsolute, 0.1, 1e-6);
  EXPECT_NEAR(e.maxAbsolute, 0.1, 1e-6);
  EXPECT_NEAR(e.psnr, 20.0, 1e-4);
  EXPECT_NEAR(e.leakShare, 1.0, 1e-12);
  EXPECT_NEAR(e.leakMeanExcess, 0.1, 1e-6);
  EXPECT_EQ(e.darkShare, 0.0);
}

TEST(Metrics, LeaksAndOverDarkeningAreSeparatedAndTheMaskApplies) {
  Image reference = filled(4, 1, 0.5f), estimate = filled(4, 1, 0.5f), mask = filled(4, 1, 1.0f);
  estimate.at(0, 0) = 0.9f;   // leak of 0.4
  estimate.at(1, 0) = 0.2f;   // over-darkening of 0.3
  estimate.at(2, 0) = 0.52f;  // within tau
  estimate.at(3, 0) = 0.0f;   // masked out
  mask.at(3, 0) = 0.0f;
  const VisibilityErrors e = measureVisibilityErrors(estimate, reference, mask, 0.05);
  EXPECT_EQ(e.pixels, 3);
  EXPECT_NEAR(e.leakShare, 1.0 / 3.0, 1e-12);
  EXPECT_NEAR(e.leakMeanExcess, 0.4, 1e-6);
  EXPECT_NEAR(e.darkShare, 1.0 / 3.0, 1e-12);
  EXPECT_NEAR(e.darkMeanExcess, 0.3, 1e-6);
  EXPECT_NEAR(e.maxAbsolute, 0.4, 1e-6);
  EXPECT_EQ(e.worstX, 0);
  EXPECT_NEAR(e.rmse, std::sqrt((0.16 + 0.09 + 0.0004) / 3.0), 1e-6);
}

TEST(Metrics, ExactImagesScoreAPerfectPsnr) {
  const Image a = filled(3, 3, 0.25f);
  const VisibilityErrors e = measureVisibilityErrors(a, a, filled(3, 3, 1.0f));
  EXPECT_EQ(e.rmse, 0.0);
  EXPECT_EQ(e.psnr, 100.0);
}

// A NaN visibility is an error that cannot be measured: it must not score as exact (PSNR 100,
// which sqrt(NaN) > 0 being false once gave) nor hide behind the finite pixels' maximum.
TEST(Metrics, NonFiniteVisibilityMakesEveryErrorNaNAndIsTheWorstPixel) {
  Image estimate = filled(4, 1, 0.5f);
  const Image reference = filled(4, 1, 0.5f), mask = filled(4, 1, 1.0f);
  estimate.at(0, 0) = 0.9f;  // a finite error of 0.4, seen before the NaN
  estimate.at(2, 0) = std::nanf("");
  estimate.at(3, 0) = INFINITY;
  const VisibilityErrors e = measureVisibilityErrors(estimate, reference, mask, 0.05);
  EXPECT_EQ(e.pixels, 4);
  EXPECT_EQ(e.nonFinitePixels, 2);
  EXPECT_TRUE(std::isnan(e.rmse));
  EXPECT_TRUE(std::isnan(e.meanAbsolute));
  EXPECT_TRUE(std::isnan(e.maxAbsolute));
  EXPECT_TRUE(std::isnan(e.psnr)) << "PSNR " << e.psnr << " for a NaN visibility";
  EXPECT_EQ(e.worstX, 2);
}

TEST(Metrics, FlickerIsTheChangeBeyondTheReferencesOwn) {
  const Image mask = filled(2, 2, 1.0f);
  const std::vector<Image> reference{filled(2, 2, 0.5f), filled(2, 2, 0.6f), filled(2, 2, 0.5f)};
  const std::vector<Image> steady{filled(2, 2, 0.5f), filled(2, 2, 0.6f), filled(2, 2, 0.5f)};
  const std::vector<Image> flickering{filled(2, 2, 0.3f), filled(2, 2, 0.7f), filled(2, 2, 0.3f)};
  const std::vector<Image> masks(3, mask);
  EXPECT_NEAR(temporalFlicker(steady, reference, masks), 0.0, 1e-9);
  // Steps of 0.4 where the reference steps by 0.1: 0.3 of flicker per pixel and frame.
  EXPECT_NEAR(temporalFlicker(flickering, reference, masks), 0.3, 1e-6);
  const std::vector<Image> opposite{filled(2, 2, 0.5f), filled(2, 2, 0.4f), filled(2, 2, 0.5f)};
  EXPECT_NEAR(temporalFlicker(opposite, reference, masks), 0.2, 1e-6);
  EXPECT_THROW(temporalFlicker(std::span(steady).first(1), std::span(reference).first(1),
                               std::span(masks).first(1)),
               Error);
}

TEST(Metrics, FrameToFrameChangeIsTheMeanStepOfTheVisibilityItself) {
  Image mask = filled(2, 2, 1.0f);
  mask.at(1, 1) = 0.0f;  // uncovered in every frame: its jump of 1 must not count
  std::vector<Image> frames{filled(2, 2, 0.5f), filled(2, 2, 0.7f), filled(2, 2, 0.4f)};
  frames[1].at(1, 1) = 1.0f;
  frames[1].at(0, 0) = 0.9f;
  const std::vector<Image> masks(3, mask);
  // Steps of 0.4, 0.2, 0.2 then 0.5, 0.3, 0.3 on the three covered pixels.
  EXPECT_NEAR(frameToFrameChange(frames, masks), (0.8 + 1.1) / 6.0, 1e-6);
  // A pixel uncovered in the middle frame counts for neither step.
  std::vector<Image> partly = masks;
  partly[1].at(0, 0) = 0.0f;
  EXPECT_NEAR(frameToFrameChange(frames, partly), (0.2 * 2 + 0.3 * 2) / 4.0, 1e-6);
  EXPECT_THROW(frameToFrameChange(std::span(frames).first(1), std::span(masks).first(1)), Error);
}

TEST(Metrics, MismatchedImagesAreRejected) {
  EXPECT_THROW(measureVisibilityErrors(filled(2, 2, 0.0f), filled(3, 2, 0.0f), filled(2, 2, 1.0f)),
               Error);
}

TEST(Metrics, LitSurfaceMaskKeepsPixelsWhereTheShadowTestDecides) {
  Image lookup(3, 1, 4, 0.0f);
  lookup.at(0, 0, 3) = 1.0f;  // inside, facing the light
  lookup.at(1, 0, 3) = 0.5f;  // inside, facing away or grazing
  const Image mask = litSurfaceMask(lookup);
  EXPECT_EQ(mask.at(0, 0), 1.0f);
  EXPECT_EQ(mask.at(1, 0), 0.0f);
  EXPECT_EQ(mask.at(2, 0), 0.0f);
}

}  // namespace
}  // namespace penumbra

namespace penumbra {
namespace {

TEST(Median, MiddleValueOrMeanOfTheMiddleTwo) {
  EXPECT_EQ(median({3.0, 1.0, 2.0}), 2.0);
  EXPECT_EQ(median({4.0, 1.0, 3.0, 2.0}), 2.5);
  EXPECT_EQ(median({7.0}), 7.0);
  EXPECT_THROW(median({}), Error);
}

}  // namespace
}  // namespace penumbra
