// CSV fields as RFC 4180 writes them: plain text as is, text with a comma, quote or line break
// quoted with its quotes doubled (the pass bench's "plain separable blur, 9 taps" had split its
// row into eight fields).
#include <gtest/gtest.h>

#include "penumbra/csv_field.h"

namespace penumbra {
namespace {

TEST(CsvField, PlainTextIsWrittenAsIs) {
  EXPECT_EQ(csvField("rg32f x 1 layer"), "rg32f x 1 layer");
  EXPECT_EQ(csvField(""), "");
}

TEST(CsvField, CommasQuotesAndLineBreaksAreQuoted) {
  EXPECT_EQ(csvField("plain separable blur, 9 taps"), "\"plain separable blur, 9 taps\"");
  EXPECT_EQ(csvField("the \"fused\" pass"), "\"the \"\"fused\"\" pass\"");
  EXPECT_EQ(csvField("two\nlines"), "\"two\nlines\"");
}

}  // namespace
}  // namespace penumbra
