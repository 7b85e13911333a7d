// Every render records the view it was made from (light and camera) in its JSON, and writes the
// settings file that gives the same picture back through --settings.
#include <gtest/gtest.h>

#include <algorithm>
#include <nlohmann/json.hpp>
#include <string>

#include "penumbra/image_io.h"
#include "run_penumbra.h"

namespace penumbra::test {
namespace {

TEST(RenderView, TheRecordNamesTheViewAndItsSettingsFileRendersThePictureAgain) {
  ScratchFolder scratch;
  // A view of the user's own, none of it the scene's default: the settings file must carry all
  // of it for the second render to see the same picture.
  const RunResult first = runPenumbra(
      {"render", "--scene",       "planar", "--technique",     "vsm",     "--light",
       "spot",   "--light-pos",   "2,6,3",  "--light-target",  "0,0,0.5", "--spot-angle",
       "70",     "--camera-pos",  "-3,4,6", "--camera-target", "0.5,0,0", "--camera-fov",
       "50",     "--shadow-size", "128",    "--width",         "96",      "--height",
       "54",     "--out",         "first"},
      scratch.path());
  ASSERT_EQ(first.exitCode(), 0) << first.output;
  const nlohmann::json record =
      nlohmann::json::parse(readFile(scratch.path() / "first" / "planar_vsm.json"));
  const nlohmann::json& view = record.at("view");
  EXPECT_EQ(view.at("light").at("kind"), "spot");
  EXPECT_EQ(view.at("light").at("position"), nlohmann::json::parse("[2.0, 6.0, 3.0]"));
  EXPECT_EQ(view.at("light").at("target"), nlohmann::json::parse("[0.0, 0.0, 0.5]"));
  EXPECT_EQ(view.at("light").at("spot_angle"), 70.0);
  EXPECT_EQ(view.at("camera").at("position"), nlohmann::json::parse("[-3.0, 4.0, 6.0]"));
  EXPECT_EQ(view.at("camera").at("target"), nlohmann::json::parse("[0.5, 0.0, 0.0]"));
  EXPECT_EQ(view.at("camera").at("fov"), 50.0);
  // Times that were measured and none that were not: llvmpipe's timer queries time the command
  // submission, so its record has no GPU times (null, not zeros); a vendor GPU's has them.
  EXPECT_GT(record.at("wall_ms").at("total").get<double>(), 0.0);
  if (record.at("device").get<std::string>().find("llvmpipe") != std::string::npos) {
    EXPECT_TRUE(record.at("gpu_ms").is_null()) << record.at("gpu_ms");
  } else {
    EXPECT_GT(record.at("gpu_ms").at("total").get<double>(), 0.0);
  }

  const RunResult again = runPenumbra(
      {"render", "--settings", (scratch.path() / "first" / "planar_vsm_settings.json").string(),
       "--out", "again"},
      scratch.path());
  ASSERT_EQ(again.exitCode(), 0) << again.output;
  const Image a = readFloatExr(scratch.path() / "first" / "planar_vsm_visibility.exr");
  const Image b = readFloatExr(scratch.path() / "again" / "planar_vsm_visibility.exr");
  ASSERT_EQ(a.width(), b.width());
  ASSERT_EQ(a.height(), b.height());
  // The same GL, settings and view: the same bits.
  EXPECT_TRUE(std::equal(a.data().begin(), a.data().end(), b.data().begin()));
}

// What loading added or left out is part of the picture: a lone box rendered without the ground
// renders without it again through its settings file.
TEST(RenderView, TheSettingsFileCarriesTheGroundAndCastersChoices) {
  ScratchFolder scratch;
  writeFile(scratch.path() / "box.obj",
            "v -0.5 0 -0.5\nv 0.5 0 -0.5\nv 0.5 1 -0.5\nv -0.5 1 -0.5\nv -0.5 0 0.5\n"
            "v 0.5 0 0.5\nv 0.5 1 0.5\nv -0.5 1 0.5\nf 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\n"
            "f 4 8 7 3\nf 1 5 8 4\nf 2 3 7 6\n");
  const RunResult first = runPenumbra(
      {"render", "--scene", "box.obj", "--technique", "hard", "--ground", "off", "--casters", "all",
       "--shadow-size", "128", "--width", "96", "--height", "54", "--out", "first"},
      scratch.path());
  ASSERT_EQ(first.exitCode(), 0) << first.output;
  const nlohmann::json settings =
      nlohmann::json::parse(readFile(scratch.path() / "first" / "box_hard_settings.json"));
  EXPECT_EQ(settings.at("ground"), "off");
  EXPECT_EQ(settings.at("casters"), "all");
  const RunResult again = runPenumbra(
      {"render", "--settings", (scratch.path() / "first" / "box_hard_settings.json").string(),
       "--out", "again"},
      scratch.path());
  ASSERT_EQ(again.exitCode(), 0) << again.output;
  const Image a = readFloatExr(scratch.path() / "first" / "box_hard_visibility.exr");
  const Image b = readFloatExr(scratch.path() / "again" / "box_hard_visibility.exr");
  ASSERT_EQ(a.data().size(), b.data().size());
  EXPECT_TRUE(std::equal(a.data().begin(), a.data().end(), b.data().begin()));
}

}  // namespace
}  // namespace penumbra::test
