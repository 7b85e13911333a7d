// The encode's minimal kernel: compiled for the layout, dispatched as the encode is.
#include "minimal_copy.h"

#include <epoxy/gl.h>

#include <string>
#include <vector>

#include "channel_dispatch.h"

namespace penumbra::gl {

MinimalCopy::MinimalCopy(ProgramCache& programs, const ChannelLayout& layout, int size)
    : layout_(layout), size_(size) {
  std::vector<ShaderDefine> defines = formatDefines(layout);
  defines.push_back({"LAYER_COUNT", std::to_string(layout.layers)});
  defines.push_back(encodeRowsDefine(layout));
  program_ = &programs.compute("passes/baseline_copy.comp", defines);
  setSize(*program_, "size", size);
}

void MinimalCopy::run(const Texture& depth, const Texture& channels) const {
  glBindTextureUnit(0, depth.id());
  bindChannelImage(channels, layout_, 0);
  const GroupGrid grid = encodeGroups(layout_, size_);
  program_->dispatch(grid.x, grid.y);
}

}  // namespace penumbra::gl
