// A view that is mostly in shadow for every technique is called out, with its likely cause:
// a closed box around a scene with the light outside it (a sky dome's case) shades every lit
// surface, and render and compare say so instead of ranking the frame silently.
#include <gtest/gtest.h>

#include <fstream>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>
#include <sstream>

#include "penumbra/image_io.h"
#include "run_penumbra.h"

namespace penumbra::test {
namespace {

// An axis-aligned box as 12 triangles (OBJ, 1-based indices after `first` vertices).
void writeBox(std::ostream& obj, glm::vec3 lo, glm::vec3 hi, int& first) {
  for (int i = 0; i < 8; ++i) {
    obj << "v " << (i & 1 ? hi.x : lo.x) << " " << (i & 2 ? hi.y : lo.y) << " "
        << (i & 4 ? hi.z : lo.z) << "\n";
  }
  const int faces[12][3] = {{0, 1, 3}, {0, 3, 2}, {4, 6, 7}, {4, 7, 5}, {0, 4, 5}, {0, 5, 1},
                            {2, 3, 7}, {2, 7, 6}, {0, 2, 6}, {0, 6, 4}, {1, 5, 7}, {1, 7, 3}};
  for (const auto& f : faces) {
    obj << "f " << first + f[0] << " " << first + f[1] << " " << first + f[2] << "\n";
  }
  first += 8;
}

// A ground slab and a block on it; with `dome`, a closed shell far around both.
std::string sceneObj(bool dome) {
  std::ostringstream obj;
  int first = 1;
  writeBox(obj, {-4.0f, -0.2f, -4.0f}, {4.0f, 0.0f, 4.0f}, first);
  writeBox(obj, {-0.5f, 0.0f, -0.5f}, {0.5f, 1.5f, 0.5f}, first);
  if (dome) writeBox(obj, {-20.0f, -1.0f, -20.0f}, {20.0f, 20.0f, 20.0f}, first);
  return obj.str();
}

const std::vector<std::string> kView{"--light",       "point", "--light-pos",     "3,30,2",
                                     "--camera-pos",  "5,4,6", "--camera-target", "0,0.5,0",
                                     "--shadow-size", "256",   "--width",         "128",
                                     "--height",      "72"};

TEST(ShadowedView, RenderWarnsWhenEnclosingGeometryShadowsEverythingAndNotOtherwise) {
  ScratchFolder scratch;
  for (bool dome : {false, true}) {
    const std::string name = dome ? "dome.obj" : "open.obj";
    writeFile(scratch.path() / name, sceneObj(dome));
    std::vector<std::string> args{
        "render", "--scene", name, "--technique", "hard,vsm", "--out", dome ? "dome" : "open"};
    args.insert(args.end(), kView.begin(), kView.end());
    const RunResult run = runPenumbra(args, scratch.path());
    ASSERT_EQ(run.exitCode(), 0) << run.output;
    const bool warned = run.output.find("in shadow for every technique") != std::string::npos;
    EXPECT_EQ(warned, dome) << run.output;
    if (dome) {
      // The light at y = 30 is above the shell's top (y = 20): the cause named is the light.
      EXPECT_NE(run.output.find(
                    "The point light at (3, 30, 2) is outside the bounds of what casts shadows"),
                std::string::npos)
          << run.output;
    }
  }
}

// The same scene with each box its own material, so its own mesh: the shell is recognised as
// enclosing the rest (docs/scenes.md, "Real models").
std::pair<std::string, std::string> sceneWithMaterials() {
  std::ostringstream obj;
  std::string mtl;
  int first = 1;
  const glm::vec3 boxes[3][2] = {{{-4.0f, -0.2f, -4.0f}, {4.0f, 0.0f, 4.0f}},
                                 {{-0.5f, 0.0f, -0.5f}, {0.5f, 1.5f, 0.5f}},
                                 {{-20.0f, -1.0f, -20.0f}, {20.0f, 20.0f, 20.0f}}};
  obj << "mtllib dome.mtl\n";
  for (int b = 0; b < 3; ++b) {
    mtl += "newmtl m" + std::to_string(b) + "\nKd 0.8 0.8 0.8\n";
    obj << "usemtl m" << b << "\n";
    writeBox(obj, boxes[b][0], boxes[b][1], first);
  }
  return {obj.str(), mtl};
}

// By default the shell casts no shadow: the block's shadow is on the floor, the rest of the floor
// is lit and nothing is called out; with --casters all the shell shadows everything again.
TEST(ShadowedView, AnEnclosingShellCastsNoShadowByDefaultAndAllCastersBringItBack) {
  ScratchFolder scratch;
  const auto [obj, mtl] = sceneWithMaterials();
  writeFile(scratch.path() / "dome.obj", obj);
  writeFile(scratch.path() / "dome.mtl", mtl);
  for (bool all : {false, true}) {
    std::vector<std::string> args{"render", "--scene", "dome.obj",          "--technique",
                                  "hard",   "--out",   all ? "all" : "auto"};
    args.insert(args.end(), kView.begin(), kView.end());
    if (all) args.insert(args.end(), {"--casters", "all"});
    const RunResult run = runPenumbra(args, scratch.path());
    ASSERT_EQ(run.exitCode(), 0) << run.output;
    const bool warned = run.output.find("in shadow for every technique") != std::string::npos;
    EXPECT_EQ(warned, all) << run.output;
    EXPECT_EQ(
        run.output.find("they cast no shadows (--casters all keeps them)") != std::string::npos,
        !all)
        << run.output;
    const Image visibility =
        readFloatExr(scratch.path() / (all ? "all" : "auto") / "dome_hard_visibility.exr");
    size_t lit = 0, shadowed = 0;
    for (int y = 0; y < visibility.height(); ++y) {
      for (int x = 0; x < visibility.width(); ++x) {
        (visibility.at(x, y) > 0.5f ? lit : shadowed) += 1;
      }
    }
    if (!all) {
      // The light at (3, 30, 2) over the block: its shadow falls towards -x, -z on the floor.
      EXPECT_GT(shadowed, 0u);
      EXPECT_GT(lit, 4 * shadowed);
    } else {
      EXPECT_EQ(lit, 0u);
    }
  }
}

TEST(ShadowedView, CompareSaysSoInItsReport) {
  ScratchFolder scratch;
  writeFile(scratch.path() / "dome.obj", sceneObj(true));
  std::vector<std::string> args{"compare", "--scene",  "dome.obj", "--technique",
                                "hard",    "--frames", "2",        "--truth",
                                "none",    "--out",    "report"};
  args.insert(args.end(), kView.begin(), kView.end());
  const RunResult run = runPenumbra(args, scratch.path());
  ASSERT_EQ(run.exitCode(), 0) << run.output;
  EXPECT_NE(run.output.find("in shadow for every technique"), std::string::npos) << run.output;
  const std::string html = readFile(scratch.path() / "report" / "index.html");
  EXPECT_NE(html.find("This frame ranks the view, not the techniques"), std::string::npos);
  const nlohmann::json metrics =
      nlohmann::json::parse(readFile(scratch.path() / "report" / "metrics.json"));
  EXPECT_TRUE(metrics.at("view_warning").is_string());
  EXPECT_EQ(metrics.at("view").at("light").at("kind"), "point");
}

}  // namespace
}  // namespace penumbra::test
