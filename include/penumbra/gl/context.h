// OpenGL 4.5 core contexts the renderer runs in: a headless one through EGL (the vendor driver
// where a GPU exists, Mesa's llvmpipe otherwise), or one a window toolkit or a host application
// made current. On penumbra's own contexts GL errors and KHR_debug messages of high severity
// become Error; a host's error queue and debug callback stay the host's unless it asks otherwise.
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

// penumbra's own context: GL errors are reported (GlErrors::Report) on this thread while it lives.
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

// Who owns the GL error state (glGetError's queue, the KHR_debug callback and debug output
// switches) of a context penumbra runs on but did not create.
enum class GlErrors {
  // The host's: penumbra leaves its debug callback, user pointer and GL_DEBUG_OUTPUT* switches
  // as they are, and checkErrors and discardPendingErrors do nothing on this thread, so errors
  // (penumbra's too) stay in the host's queue and reach the host's callback.
  LeaveToHost,
  // penumbra's, as on HeadlessContext: it enables synchronous debug output, installs its own
  // callback, and checkErrors drains glGetError and throws what it finds. For a window penumbra
  // itself opened (the viewer's).
  Report,
};

// A context someone else created and made current on this thread (a host's, or a GLFW window's;
// calling GL without a current context is undefined, so it must be current already): checks that
// it is OpenGL 4.5 core, throws Error otherwise. It does not own the context, which must outlive
// the renderer. `errors` applies on this thread while this object lives; contexts made on one
// thread must be destroyed in the reverse order of their creation, which restores the policy of
// the one before. A thread with no penumbra context object leaves errors to the host.
class CurrentContext final : public Context {
 public:
  explicit CurrentContext(GlErrors errors = GlErrors::LeaveToHost);
  ~CurrentContext();
  CurrentContext(const CurrentContext&) = delete;
  CurrentContext& operator=(const CurrentContext&) = delete;

  std::string description() const override;

 private:
  GlErrors previous_;
};

// With GlErrors::Report on this thread (HeadlessContext, or a CurrentContext that asked for it):
// throws Error naming `where` if glGetError reports an error or KHR_debug logged one. With
// GlErrors::LeaveToHost: does nothing.
void checkErrors(const char* where);
// Drops the GL errors and KHR_debug messages pending now, for a failure already reported in full
// (a shader's compile log): otherwise the next checkErrors would report it again, as its own.
// Does nothing with GlErrors::LeaveToHost: the queue is the host's.
void discardPendingErrors();

}  // namespace penumbra::gl
