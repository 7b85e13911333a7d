// OpenGL 4.5 core contexts the renderer runs in: a headless one through EGL (the vendor driver
// where a GPU exists, Mesa's llvmpipe otherwise), or one a window toolkit made current (the
// viewer's GLFW window). GL errors and KHR_debug messages of high severity become Error.
#pragma once

#include <memory>
#include <string>

namespace penumbra::gl {

// "A GL 4.5 core context is current on this thread": what the renderer needs, whoever made it.
class Context {
 public:
  virtual ~Context() = default;
  // GL_RENDERER and GL_VERSION, e.g. "llvmpipe (LLVM 15.0.6, 256 bits), 4.5 (Core Profile) Mesa".
  virtual std::string description() const = 0;
};

class HeadlessContext final : public Context {
 public:
  // Makes the context current on this thread; throws Error naming what is missing (EGL display,
  // GL 4.5 core support, surfaceless or pbuffer surfaces).
  HeadlessContext();
  ~HeadlessContext();
  HeadlessContext(const HeadlessContext&) = delete;
  HeadlessContext& operator=(const HeadlessContext&) = delete;

  std::string description() const override;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// A context someone else created and made current on this thread (a GLFW window's; calling GL
// without a current context is undefined, so it must be current already): checks that it is
// OpenGL 4.5 core and routes its KHR_debug errors to checkErrors like HeadlessContext's.
// Throws Error otherwise. It does not own the context, which must outlive the renderer.
class CurrentContext final : public Context {
 public:
  CurrentContext();
  std::string description() const override;
};

// Throws Error naming `where` if glGetError reports an error or KHR_debug logged one.
void checkErrors(const char* where);
// Drops the GL errors and KHR_debug messages pending now, for a failure already reported in full
// (a shader's compile log): otherwise the next checkErrors would report it again, as its own.
void discardPendingErrors();

}  // namespace penumbra::gl
