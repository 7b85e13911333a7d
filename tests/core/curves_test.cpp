// Curve tables written as CSV: names that would break the header are refused.
#include <gtest/gtest.h>

#include <filesystem>

#include "penumbra/curves.h"
#include "penumbra/error.h"

namespace penumbra {
namespace {

TEST(Curves, CsvRefusesAColumnNameWithAComma) {
  CurvesTable t;
  t.receiverDepths = {0.0f, 1.0f};
  t.columns = {"exact", "M = 16, scale 2"};
  t.values = {{1.0f, 0.0f}, {1.0f, 0.0f}};
  const std::filesystem::path csv = std::filesystem::temp_directory_path() / "comma_curves.csv";
  EXPECT_THROW(writeCurvesCsv(t, csv), Error);
  t.columns[1] = "M = 16; scale 2";
  EXPECT_NO_THROW(writeCurvesCsv(t, csv));
  std::filesystem::remove(csv);
}

}  // namespace
}  // namespace penumbra
