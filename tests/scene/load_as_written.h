// Loading a scene file for tests of its loader: the geometry the file describes, without the
// ground loadScene adds under a lone model (SceneLoadOptions::ground), which the shaping tests
// (scene_shaping_test.cpp) cover.
#pragma once

#include <string>

#include "penumbra/scene.h"

namespace penumbra::testing {

inline Scene loadAsWritten(const std::string& path, SceneLoadOptions options = {}) {
  options.ground = GroundMode::Off;
  return loadScene(path, options);
}

}  // namespace penumbra::testing
