// penumbra-glsl-amalgamate OUTDIR: writes penumbra_<technique>.glsl per technique, the GLSL entry
// point penumbraShadow() (lib/penumbra_shadow.glsl) with everything it includes pasted in once,
// for hosts whose GL has no ARB_shading_language_include (docs/integration.md). Run at build
// time; the files are installed under share/penumbra/glsl.
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

#include "penumbra/shader_library.h"
#include "penumbra/technique.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: penumbra-glsl-amalgamate OUTDIR\n";
    return 2;
  }
  const std::filesystem::path out = argv[1];
  std::filesystem::create_directories(out);
  const penumbra::ShaderLibrary library;
  const std::string body = library.amalgamate("lib/penumbra_shadow.glsl");
  for (penumbra::Technique t : penumbra::allTechniques()) {
    const std::string id(penumbra::techniqueId(t));
    const std::string number = std::to_string(int(t));
    std::ofstream file(out / ("penumbra_" + id + ".glsl"), std::ios::binary);
    file << "// penumbra " << id << ": penumbraShadow() and everything it needs, generated from\n"
         << "// src/shaders by penumbra-glsl-amalgamate. Put it after `#version 450 core` and\n"
         << "// ShadowFilter::shaderPreamble() (docs/integration.md).\n"
         << "#if SUMMED_AREA\n#extension GL_ARB_gpu_shader_int64 : require\n#endif\n"
         << "#ifndef TECHNIQUE_ID\n#define TECHNIQUE_ID " << number << "\n#endif\n"
         << "#if TECHNIQUE_ID != " << number << "\n"
         << "#error \"penumbra_" << id << ".glsl is " << id
         << "'s; the filter's preamble names another technique\"\n#endif\n"
         << body;
    if (!file) {
      std::cerr << "cannot write " << (out / ("penumbra_" + id + ".glsl")).string() << "\n";
      return 1;
    }
  }
  return 0;
}
