// GLSL sources compiled into the binary, and the loader that turns them into compilable text:
// `#include "..."` resolved (relative to the including file, then to the shader root), `#line`
// directives so compiler messages name the real file and line, and a generated `#version 450
// core` plus `#define`s for variants.
#pragma once

#include <map>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace penumbra {

struct EmbeddedShaderFile {
  std::string_view path;  // relative to src/shaders, e.g. "shared/vsm.h"
  std::string_view source;
};

// Every file under src/shaders (shared/, lib/, passes/), embedded at build time.
std::span<const EmbeddedShaderFile> embeddedShaderFiles();

struct ShaderDefine {
  std::string name;
  std::string value;
};

// Expanded source plus the file behind each `#line` source-string number.
struct ExpandedShader {
  std::string source;
  std::vector<std::string> files;

  // Rewrites compiler log locations "N:LINE" (Mesa, glslang) and "N(LINE)" (NVIDIA) into
  // "file:LINE".
  std::string translateLog(std::string_view log) const;
};

class ShaderLibrary {
 public:
  // Holds the embedded files.
  ShaderLibrary();

  // Adds or replaces a file (tests and tools add their own shaders).
  void addFile(std::string path, std::string source);
  bool contains(std::string_view path) const;
  std::vector<std::string> paths() const;

  // Throws Error for a missing file or include, a `#version` line in a file, or include cycles.
  ExpandedShader expand(std::string_view path, std::span<const ShaderDefine> defines = {}) const;
  // The file with every include pasted in once, without #version or #line: resolver-free GLSL
  // a host pastes into its own shader (the installed penumbra_<technique>.glsl files).
  std::string amalgamate(std::string_view path) const;

 private:
  std::map<std::string, std::string, std::less<>> files_;
};

}  // namespace penumbra
