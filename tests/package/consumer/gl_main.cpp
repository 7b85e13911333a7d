// Builds against penumbra::gl from the installed package: the filtering API's header, a generic
// name that must not resolve to penumbra's (image.h is penumbra/image.h only), and the installed
// amalgamated GLSL the package points at. No GL context here: building and linking is the test.
#include <penumbra/gl/shadow_filter.h>

#include <cstdio>
#include <fstream>
#include <string>

#if __has_include(<image.h>) || __has_include(<scene.h>) || __has_include(<filters.h>) || \
    __has_include(<params.h>) || __has_include(<shared/vsm.h>)
#error "a generic penumbra header name reached the consumer's include path"
#endif

int main() {
  // A symbol of the GL library itself, so linking penumbra::gl (and its usage requirements:
  // epoxy, the core) is part of the test, not only its header.
  void (penumbra::gl::ShadowFilter::*filter)(const penumbra::gl::DepthInput&,
                                             const penumbra::gl::FilterSettings&) =
      &penumbra::gl::ShadowFilter::filter;
  volatile bool linked = filter != nullptr;
  const penumbra::gl::ShadowBindings bindings;
  std::ifstream glsl(std::string(PENUMBRA_GLSL_DIR) + "/penumbra_vsm.glsl");
  std::string first;
  std::getline(glsl, first);
  std::printf("lookup block at %d; %s\n", bindings.lookupBlock, first.c_str());
  return linked && first.find("penumbra vsm") != std::string::npos ? 0 : 1;
}
