// The unfiltered depth every technique starts from: penumbra's linear depth metric
// (shared/light_depth.h) in an R32F 2D array, one layer per map layer (cascade, point-light
// face), multisampled or not. The light pass makes it; ShadowFilter imports a host's depth
// texture into it.
#pragma once

namespace penumbra::gl {

struct LinearDepthMaps {
  unsigned texture = 0;  // GL_TEXTURE_2D_ARRAY, or GL_TEXTURE_2D_MULTISAMPLE_ARRAY (samples > 1)
  int size = 0;          // texels per side
  int layers = 1;
  int samples = 1;
  bool multisampled() const { return samples > 1; }
};

}  // namespace penumbra::gl
