// The example's command line: the technique and its settings, the view (the same values go to
// `penumbra render`), and what to write.
#pragma once

#include <glm/glm.hpp>
#include <string>
#include <vector>

struct Options {
  std::string technique = "evsm4";
  std::vector<std::string> params;  // NAME=VALUE or TECHNIQUE.NAME=VALUE
  int size = 512, width = 320, height = 180, blurTaps = 3;
  std::string filter = "bilinear";
  // window: a D32F depth texture (WindowDepth); linear: R32F of penumbra's metric (LinearDepth).
  std::string depth = "window";
  glm::vec3 lightDir{0.75f, -1.0f, -0.5f};
  glm::vec3 cameraPos{0.0f, 3.5f, 6.0f}, cameraTarget{0.0f, 0.5f, 0.0f};
  float cameraFov = 45.0f;
  std::string glslDir = PENUMBRA_EMBED_GLSL_DIR;  // the installed share/penumbra/glsl
  std::string writeObj, out;
  bool checkState = false;
};

// Throws std::runtime_error naming an unknown option or a malformed value.
Options parseOptions(int argc, char** argv);
const char* optionsUsage();
