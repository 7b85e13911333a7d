// A headless OpenGL 4.5 core context through EGL: the vendor driver where a GPU exists, Mesa's
// llvmpipe otherwise. GL errors and KHR_debug messages of high severity become Error.
#pragma once

#include <memory>
#include <string>

namespace penumbra::gl {

class HeadlessContext {
 public:
  // Makes the context current on this thread; throws Error naming what is missing (EGL display,
  // GL 4.5 core support, surfaceless or pbuffer surfaces).
  HeadlessContext();
  ~HeadlessContext();
  HeadlessContext(const HeadlessContext&) = delete;
  HeadlessContext& operator=(const HeadlessContext&) = delete;

  // GL_RENDERER and GL_VERSION, e.g. "llvmpipe (LLVM 15.0.6, 256 bits), 4.5 (Core Profile) Mesa".
  std::string description() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// Throws Error naming `where` if glGetError reports an error or KHR_debug logged one.
void checkErrors(const char* where);
// Drops the GL errors and KHR_debug messages pending now, for a failure already reported in full
// (a shader's compile log): otherwise the next checkErrors would report it again, as its own.
void discardPendingErrors();

}  // namespace penumbra::gl
