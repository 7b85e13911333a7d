// penumbra compare's measurements against the papers' claims: VSM exact on the planar scene,
// light-leak ordering on the bench scene.
#include <gtest/gtest.h>

#include "gl_test_context.h"
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "penumbra/compare/comparison.h"
#include "penumbra/compare/report.h"
#include "penumbra/image_io.h"
#include "penumbra/error.h"

namespace penumbra {
namespace {

class ComparisonTest : public testing::GlTest {
 protected:
  void SetUp() override {
    GlTest::SetUp();
    if (context) renderer = std::make_unique<gl::Renderer>(*context);
  }

  compare::ComparisonRequest request(const char* scene, std::vector<Technique> techniques) const {
    compare::ComparisonRequest r;
    r.scene = scene;
    r.techniques = std::move(techniques);
    r.settings.shadowMapSize = 512;
    r.settings.width = 480;
    r.settings.height = 270;
    r.settings.blur = {BlurKernel::Box, 3, 1.0f};
    r.settings.filter = gl::FilterMode::Bilinear;
    r.supersample = 2;
    r.pathFrames = 2;
    return r;
  }
  // VSM and PCF on the bench scene, small: for what the report writes of a result.
  compare::ComparisonResult smallVsmAndPcfComparison() const {
    compare::ComparisonRequest q = request("bench", {Technique::Vsm, Technique::Pcf});
    q.settings.shadowMapSize = 128;
    q.settings.width = 64;
    q.settings.height = 36;
    return compare::runComparison(q, *renderer);
  }

  const compare::TechniqueResult& find(const compare::ComparisonResult& r, Technique t) {
    for (const auto& k : r.techniques) {
      if (k.technique == t) return k;
    }
    throw Error("missing technique");
  }

  std::unique_ptr<gl::Renderer> renderer;
};

TEST_F(ComparisonTest, VsmMatchesTheFilteredReferenceOnThePlanarScene) {
  const compare::ComparisonResult r =
      compare::runComparison(request("planar", {Technique::Vsm, Technique::Pcf}), *renderer);
  EXPECT_LT(find(r, Technique::Vsm).filtered.rmse, 1e-3);
  EXPECT_LT(find(r, Technique::Pcf).filtered.rmse, 1e-5)
      << "PCF of the same kernel is the reference";
  EXPECT_GT(find(r, Technique::Vsm).filtered.pixels, 10000);
}

// compare's first frame reads ESM's diagnostic back, where its failure rate is counted (a frame
// that reads no diagnostic counts none): the backyard's curved casters fail the threshold test
// on a few percent of the pixels (EsmFailureRateGrowsWithTheBlurAsInTheEsmPapersTable3).
TEST_F(ComparisonTest, EsmsFailureRateIsReported) {
  const compare::ComparisonResult r =
      compare::runComparison(request("backyard", {Technique::Esm}), *renderer);
  EXPECT_GT(find(r, Technique::Esm).failureRatePercent, 0.1);
}

TEST_F(ComparisonTest, BenchLeakOrderingFollowsThePapers) {
  const compare::ComparisonResult r = compare::runComparison(
      request("bench", {Technique::Vsm, Technique::Evsm4, Technique::Lvsm, Technique::PowerCdf}),
      *renderer);
  const double vsm = find(r, Technique::Vsm).filtered.leakShare;
  RecordProperty("vsm_leak_share", std::to_string(vsm));
  EXPECT_GT(vsm, find(r, Technique::Evsm4).filtered.leakShare);
  EXPECT_GT(vsm, find(r, Technique::Lvsm).filtered.leakShare);
  EXPECT_GT(vsm, find(r, Technique::PowerCdf).filtered.leakShare);
  auto csm = [&](int terms) {
    compare::ComparisonRequest q = request("bench", {Technique::Csm});
    q.settings.params.csm.termCount = terms;
    return find(compare::runComparison(q, *renderer), Technique::Csm).filtered.leakShare;
  };
  const double csm4 = csm(4), csm16 = csm(16);
  RecordProperty("csm4_leak_share", std::to_string(csm4));
  RecordProperty("csm16_leak_share", std::to_string(csm16));
  EXPECT_GT(csm4, csm16);
}

TEST_F(ComparisonTest, ImpossiblePairsFailBeforeAnythingRenders) {
  compare::ComparisonRequest q = request("backyard", {Technique::PowerCdf});
  q.settings.filter = gl::FilterMode::SummedArea;
  try {
    compare::validateRequest(q, *renderer);
    FAIL() << "power-CDF with a summed-area table must be refused";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot run with technique 'powercdf'"), std::string::npos)
        << e.what();
  }
  q = request("garden", {Technique::Vsm});
  EXPECT_THROW(compare::validateRequest(q, *renderer), Error);
}

}  // namespace
}  // namespace penumbra

namespace penumbra {
namespace {

TEST_F(ComparisonTest, MipMappedReferenceRefusesANonPowerOfTwoShadowMap) {
  compare::ComparisonRequest q = request("planar", {Technique::Vsm});
  q.settings.shadowMapSize = 500;
  q.settings.filter = FilterMode::Trilinear;
  try {
    compare::validateRequest(q, *renderer);
    FAIL() << "a 500^2 map with trilinear lookups must be refused";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("500 is not: use 256 or 512"), std::string::npos)
        << e.what();
  }
  q.settings.filter = FilterMode::Bilinear;  // no mips: any size
  EXPECT_NO_THROW(compare::validateRequest(q, *renderer));
}

}  // namespace
}  // namespace penumbra

namespace penumbra {
namespace {

TEST_F(ComparisonTest, MatchedPcfIsTheReferenceForGaussianBlursToo) {
  // Gaussian blur + bilinear lookups: the reference kernel is the Gaussian convolved with the
  // bilinear tent around floor(position - 1/2); PCF with the plain Gaussian around
  // floor(position) is half a texel off and untented. On a scene of edges both must agree to the
  // reference's own rounding (1e-5) where the shadow test decides the shading.
  for (const char* scene : {"planar", "bench"}) {
    compare::ComparisonRequest q = request(scene, {Technique::Pcf});
    q.settings.blur = {BlurKernel::Gaussian, 3, 1.5f};
    for (FilterMode f : {FilterMode::Point, FilterMode::Bilinear}) {
      q.settings.filter = f;
      const compare::ComparisonResult r = compare::runComparison(q, *renderer);
      EXPECT_LT(find(r, Technique::Pcf).filtered.rmse, 1e-5) << scene << " " << filterModeName(f);
    }
  }
}

}  // namespace
}  // namespace penumbra

namespace penumbra {
namespace {

// The report shows visibility as a quantity: each PNG's grey level is the visibility itself
// (16-bit, no sRGB curve), so 0.5 reads back as 0.5, not as its sRGB encoding (0.735).
TEST_F(ComparisonTest, ReportVisibilityImagesHoldTheVisibilityItself) {
  compare::ComparisonRequest q = request("bench", {Technique::Vsm});
  q.settings.shadowMapSize = 128;
  q.settings.width = 64;
  q.settings.height = 36;
  const compare::ComparisonResult r = compare::runComparison(q, *renderer);
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("penumbra-report-" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  compare::writeReportFiles(r, dir);
  const Image vsm = readGrey16Png(dir / "images" / "vsm_visibility.png");
  const Image reference = readGrey16Png(dir / "images" / "reference_visibility.png");
  std::filesystem::remove_all(dir);
  ASSERT_EQ(vsm.data().size(), r.techniques[0].visibility.data().size());
  double worst = 0.0;
  for (size_t i = 0; i < vsm.data().size(); ++i) {
    worst = std::max(worst, double(std::abs(vsm.data()[i] - r.techniques[0].visibility.data()[i])));
    worst = std::max(worst, double(std::abs(reference.data()[i] - r.referenceVisibility.data()[i])));
  }
  EXPECT_LE(worst, 0.5 / 65535.0 + 1e-7);  // 16-bit rounding
}

}  // namespace
}  // namespace penumbra

namespace penumbra {
namespace {

// The ranking once sorted with `rmse <` alone: a NaN RMSE (a visibility that is not a number) is
// no strict weak order, and it landed between finite ones.
TEST(ComparisonRanking, SortsByRmseAndPutsANaNErrorLast) {
  compare::ComparisonResult r;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<std::pair<Technique, double>> rows{{Technique::Vsm, 0.2},
                                                       {Technique::Esm, nan},
                                                       {Technique::Csm, 0.1},
                                                       {Technique::Msm, 0.05},
                                                       {Technique::Lvsm, 0.1}};
  for (const auto& [t, rmse] : rows) {
    compare::TechniqueResult k;
    k.technique = t;
    k.params = defaultTechniqueParams();
    k.filtered.rmse = rmse;
    r.techniques.push_back(k);
  }
  std::vector<Technique> order;
  for (const compare::TechniqueResult* t : compare::rankTechniques(r))
    order.push_back(t->technique);
  // Ties keep the request's order (csm before lvsm).
  EXPECT_EQ(order, (std::vector<Technique>{Technique::Msm, Technique::Csm, Technique::Lvsm,
                                           Technique::Vsm, Technique::Esm}));
}

}  // namespace
}  // namespace penumbra

namespace penumbra {
namespace {

// --filter anisotropic filters every channel through the probes the filtered reference models,
// so VSM, exact on the planar scene (thesis §3.2), stays at the reference: 1.2e-4 measured, the
// 1e-3 of the bilinear test above. Mean channels once went through the driver's own anisotropic
// kernel (now anisotropic-driver), 3e-3 from the reference on llvmpipe and 0.11 on lantern: a
// penalty that min/max/log-space channels, filtered by the probes, did not pay.
TEST_F(ComparisonTest, VsmStaysAtTheReferenceUnderAnisotropicLookupsOnThePlanarScene) {
  compare::ComparisonRequest q = request("planar", {Technique::Vsm});
  q.settings.shadowMapSize = 256;
  q.settings.width = 160;
  q.settings.height = 90;
  q.settings.filter = FilterMode::Anisotropic;
  const compare::ComparisonResult r = compare::runComparison(q, *renderer);
  EXPECT_LT(find(r, Technique::Vsm).filtered.rmse, 1e-3);
  EXPECT_GT(find(r, Technique::Vsm).filtered.pixels, 5000);
  EXPECT_EQ(parseFilterMode("anisotropic-driver"), FilterMode::AnisotropicDriver);
}

}  // namespace
}  // namespace penumbra

namespace penumbra {
namespace {

// A technique whose visibility is NaN at a pixel still gets a report (the PNG writers refuse NaN,
// which once failed the whole report): its errors are NaN (null in metrics.json, with the count),
// it ranks last, and the page says which pixels were drawn in place of NaN.
TEST_F(ComparisonTest, AReportWithANaNVisibilityIsWrittenWithTheTechniqueLast) {
  compare::ComparisonResult r = smallVsmAndPcfComparison();
  compare::TechniqueResult& vsm = r.techniques[0];
  int x = 0, y = 0;
  while (r.coverage.at(x, y) <= 0.5f) {  // a covered pixel
    if (++x == r.coverage.width()) x = 0, ++y;
  }
  vsm.visibility.at(x, y) = std::numeric_limits<float>::quiet_NaN();
  vsm.filtered = measureVisibilityErrors(vsm.visibility, r.referenceVisibility, r.coverage);
  vsm.error = signedVisibilityError(vsm.visibility, r.referenceVisibility, r.coverage);
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("penumbra-nan-report-" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  EXPECT_NO_THROW(compare::writeReportFiles(r, dir));
  std::ifstream metrics(dir / "metrics.json"), page(dir / "index.html");
  const std::string text((std::istreambuf_iterator<char>(metrics)), {});
  const std::string html((std::istreambuf_iterator<char>(page)), {});
  std::filesystem::remove_all(dir);
  EXPECT_NE(html.find("1 covered pixels are not a number"), std::string::npos);
  EXPECT_NE(text.find("\"non_finite_pixels\": 1"), std::string::npos);
  EXPECT_NE(text.find("\"psnr_db\": null"), std::string::npos);
  EXPECT_EQ(compare::rankTechniques(r).back()->technique, Technique::Vsm);
}

// The report prints GPU times only where they were measured: the comparison carries the
// renderer's (none on llvmpipe, whose queries time the submission); a result without them gets
// null in metrics.json, an empty CSV field and no GPU column, never a measured-looking 0; with one
// technique's times given, the column shows them and a dash for the other.
TEST_F(ComparisonTest, GpuTimesAppearOnlyWhereTheyWereMeasured) {
  compare::ComparisonResult r = smallVsmAndPcfComparison();
  ASSERT_EQ(r.techniques.size(), 2u);
  for (const compare::TechniqueResult& t : r.techniques) {
    EXPECT_EQ(t.gpuTimes.has_value(), renderer->timerQueriesMeasureExecution());
  }
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("penumbra-gpu-times-" + std::to_string(getpid()));
  struct Files {
    nlohmann::json metrics;
    std::string html;
    std::vector<std::string> csvHeader, vsmCsvRow, pcfCsvRow;
  };
  auto fields = [](const std::string& line) {
    std::vector<std::string> out;
    std::istringstream in(line);
    for (std::string field; std::getline(in, field, ',');) out.push_back(field);
    if (!line.empty() && line.back() == ',') out.emplace_back();
    return out;
  };
  auto write = [&] {
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    compare::writeReportFiles(r, dir);
    std::ifstream metrics(dir / "metrics.json"), page(dir / "index.html"), csv(dir / "metrics.csv");
    Files f;
    f.metrics = nlohmann::json::parse(metrics);
    f.html = std::string(std::istreambuf_iterator<char>(page), {});
    std::string line;
    std::getline(csv, line);
    f.csvHeader = fields(line);
    while (std::getline(csv, line)) {
      if (line.rfind("vsm,", 0) == 0) f.vsmCsvRow = fields(line);
      if (line.rfind("pcf,", 0) == 0) f.pcfCsvRow = fields(line);
    }
    return f;
  };
  auto field = [](const Files& f, const std::vector<std::string>& row, const char* name) {
    const size_t at = size_t(std::ranges::find(f.csvHeader, name) - f.csvHeader.begin());
    return at < row.size() && row.size() == f.csvHeader.size() ? row[at] : "(no such field)";
  };

  for (compare::TechniqueResult& t : r.techniques) t.gpuTimes.reset();
  const Files none = write();
  ASSERT_EQ(none.metrics.at("techniques").size(), 2u);
  for (const nlohmann::json& t : none.metrics.at("techniques")) {
    EXPECT_TRUE(t.at("gpu_ms").is_null());
  }
  EXPECT_EQ(none.html.find("GPU ms</th>"), std::string::npos);
  EXPECT_NE(none.html.find("no GPU ms"), std::string::npos);
  EXPECT_GT(std::stod(field(none, none.vsmCsvRow, "wall_ms")), 0.0);
  EXPECT_EQ(field(none, none.vsmCsvRow, "gpu_ms"), "");

  // Techniques are listed VSM then PCF: times for the second only, so a column decided by the
  // first technique alone would be missing.
  gl::PassTimes measured;
  measured.camera = 2.5;
  r.techniques[1].gpuTimes = measured;
  const Files one = write();
  std::filesystem::remove_all(dir);
  const nlohmann::json& techniques = one.metrics.at("techniques");
  EXPECT_TRUE(techniques.at(0).at("gpu_ms").is_null());
  EXPECT_EQ(techniques.at(1).at("gpu_ms").at("camera"), 2.5);
  EXPECT_EQ(techniques.at(1).at("gpu_ms").at("total"), 2.5);
  EXPECT_EQ(field(one, one.pcfCsvRow, "gpu_ms"), "2.5");
  EXPECT_EQ(field(one, one.vsmCsvRow, "gpu_ms"), "");
  EXPECT_NE(one.html.find("GPU ms</th>"), std::string::npos);
  EXPECT_EQ(one.html.find("no GPU ms"), std::string::npos);
  EXPECT_NE(one.html.find("<td>2.5</td>"), std::string::npos);
  EXPECT_NE(one.html.find("<td>—</td>"), std::string::npos);
}

}  // namespace
}  // namespace penumbra
