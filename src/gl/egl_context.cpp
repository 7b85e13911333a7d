// EGL display selection (device platform, Mesa surfaceless, default), GL 4.5 core context, and
// the GL error path with its per-thread policy (whose errors they are).
#include <dlfcn.h>
#include <epoxy/egl.h>
#include <epoxy/gl.h>
#include <link.h>

#include <cstring>
#include <mutex>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "penumbra/error.h"
#include "penumbra/gl/context.h"

namespace penumbra::gl {
namespace {

std::mutex gDebugMutex;
std::string gDebugErrors;  // high-severity KHR_debug messages since the last checkErrors

// Per thread, as a context is current on one thread. A thread where penumbra made no context
// object runs on someone else's context: its errors are the host's.
thread_local GlErrors tErrors = GlErrors::LeaveToHost;

void GLAPIENTRY onDebugMessage(GLenum, GLenum type, GLuint, GLenum severity, GLsizei,
                               const GLchar* message, const void*) {
  if (type == GL_DEBUG_TYPE_ERROR || severity == GL_DEBUG_SEVERITY_HIGH) {
    std::lock_guard lock(gDebugMutex);
    gDebugErrors += std::string(message) + "\n";
  }
}

void routeDebugMessages() {
  glEnable(GL_DEBUG_OUTPUT);
  glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
  glDebugMessageCallback(onDebugMessage, nullptr);
}

std::string currentDescription() {
  return std::string(reinterpret_cast<const char*>(glGetString(GL_RENDERER))) + ", " +
         reinterpret_cast<const char*>(glGetString(GL_VERSION));
}

bool hasExtension(const char* list, const char* name) {
  if (list == nullptr) return false;
  const size_t length = std::strlen(name);
  for (const char* p = std::strstr(list, name); p != nullptr; p = std::strstr(p + 1, name)) {
    if ((p == list || p[-1] == ' ') && (p[length] == ' ' || p[length] == '\0')) return true;
  }
  return false;
}

// Candidate displays in order of preference: each EGL device (vendor GPUs), Mesa's surfaceless
// platform (llvmpipe without a window system), then the default display.
std::vector<EGLDisplay> candidateDisplays() {
  std::vector<EGLDisplay> displays;
  const char* clientExtensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (hasExtension(clientExtensions, "EGL_EXT_device_enumeration") &&
      hasExtension(clientExtensions, "EGL_EXT_platform_device")) {
    EGLDeviceEXT devices[16];
    EGLint count = 0;
    if (eglQueryDevicesEXT(16, devices, &count)) {
      for (EGLint i = 0; i < count; ++i) {
        EGLDisplay d = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
        if (d != EGL_NO_DISPLAY) displays.push_back(d);
      }
    }
  }
  if (hasExtension(clientExtensions, "EGL_MESA_platform_surfaceless")) {
    EGLDisplay d =
        eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (d != EGL_NO_DISPLAY) displays.push_back(d);
  }
  EGLDisplay d = eglGetDisplay(EGL_DEFAULT_DISPLAY);
  if (d != EGL_NO_DISPLAY) displays.push_back(d);
  return displays;
}

#if defined(__SANITIZE_ADDRESS__)
#define PENUMBRA_ADDRESS_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define PENUMBRA_ADDRESS_SANITIZER 1
#endif
#endif

// LeakSanitizer checks after the exit handlers, by which time EGL has dlclose'd Mesa's DRI driver:
// the blocks only the driver's globals pointed to then look leaked (112 bytes on llvmpipe), and
// their allocating frames name whatever is mapped at those addresses now, so no suppression can
// match them. Under AddressSanitizer the driver therefore stays loaded to the end of the process
// (RTLD_NODELETE): its globals are scanned, and any leak of its own names it
// (cmake/lsan_suppressions.txt). Other builds unload it as usual.
void keepDriverLoadedForLeakSanitizer() {
#ifdef PENUMBRA_ADDRESS_SANITIZER
  std::vector<std::string> drivers;
  dl_iterate_phdr(
      [](dl_phdr_info* info, size_t, void* found) {
        const std::string_view name = info->dlpi_name != nullptr ? info->dlpi_name : "";
        if (name.ends_with("_dri.so"))
          static_cast<std::vector<std::string>*>(found)->emplace_back(name);
        return 0;
      },
      &drivers);
  // Outside the iteration, which holds the loader's lock. The handle is kept on purpose.
  for (const std::string& driver : drivers) {
    dlopen(driver.c_str(), RTLD_LAZY | RTLD_NOLOAD | RTLD_NODELETE);
  }
#endif
}

}  // namespace

struct HeadlessContext::State {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  EGLSurface surface = EGL_NO_SURFACE;
  GlErrors previousErrors = GlErrors::LeaveToHost;
};

HeadlessContext::HeadlessContext() : state_(std::make_unique<State>()) {
  std::string attempts;
  for (EGLDisplay display : candidateDisplays()) {
    EGLint major = 0, minor = 0;
    if (!eglInitialize(display, &major, &minor)) {
      attempts += "  a display failed eglInitialize\n";
      continue;
    }
    const char* extensions = eglQueryString(display, EGL_EXTENSIONS);
    const bool surfaceless = hasExtension(extensions, "EGL_KHR_surfaceless_context");
    const EGLint configAttributes[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE,
                                       surfaceless ? 0 : EGL_PBUFFER_BIT, EGL_NONE};
    EGLConfig config = nullptr;
    EGLint configCount = 0;
    if (!eglBindAPI(EGL_OPENGL_API) ||
        !eglChooseConfig(display, configAttributes, &config, 1, &configCount) || configCount == 0) {
      attempts += std::string("  ") + eglQueryString(display, EGL_VENDOR) +
                  ": no OpenGL-renderable EGL config\n";
      eglTerminate(display);
      continue;
    }
    const EGLint contextAttributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                        4,
                                        EGL_CONTEXT_MINOR_VERSION,
                                        5,
                                        EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                        EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
#ifndef NDEBUG
                                        EGL_CONTEXT_OPENGL_DEBUG,
                                        EGL_TRUE,
#endif
                                        EGL_NONE};
    EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, contextAttributes);
    if (context == EGL_NO_CONTEXT) {
      attempts += std::string("  ") + eglQueryString(display, EGL_VENDOR) +
                  ": no OpenGL 4.5 core context\n";
      eglTerminate(display);
      continue;
    }
    EGLSurface surface = EGL_NO_SURFACE;
    if (!surfaceless) {
      const EGLint pbufferAttributes[] = {EGL_WIDTH, 1, EGL_HEIGHT, 1, EGL_NONE};
      surface = eglCreatePbufferSurface(display, config, pbufferAttributes);
    }
    if (!eglMakeCurrent(display, surface, surface, context)) {
      attempts += std::string("  ") + eglQueryString(display, EGL_VENDOR) +
                  ": cannot make the context current (no surfaceless or pbuffer support)\n";
      eglDestroyContext(display, context);
      eglTerminate(display);
      continue;
    }
    state_->display = display;
    state_->context = context;
    state_->surface = surface;
    keepDriverLoadedForLeakSanitizer();
    if (epoxy_gl_version() < 45) {
      throw Error("EGL gave an OpenGL " + std::to_string(epoxy_gl_version()) +
                  " context; penumbra needs 4.5 core");
    }
    routeDebugMessages();
    state_->previousErrors = std::exchange(tErrors, GlErrors::Report);
    return;
  }
  throw Error("cannot create a headless OpenGL 4.5 core context through EGL" +
              (attempts.empty() ? std::string(": no EGL display (install libegl-mesa0 and "
                                              "libgl1-mesa-dri, see scripts/install-deps)")
                                : ":\n" + attempts));
}

HeadlessContext::~HeadlessContext() {
  if (state_->display == EGL_NO_DISPLAY) return;
  tErrors = state_->previousErrors;
  eglMakeCurrent(state_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  if (state_->surface != EGL_NO_SURFACE) eglDestroySurface(state_->display, state_->surface);
  eglDestroyContext(state_->display, state_->context);
  eglTerminate(state_->display);
}

std::string HeadlessContext::description() const {
  return currentDescription();
}

CurrentContext::CurrentContext(GlErrors errors) : previous_(tErrors) {
  GLint profile = 0;
  glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
  if (epoxy_gl_version() < 45 || (profile & GL_CONTEXT_CORE_PROFILE_BIT) == 0) {
    throw Error("the current context is OpenGL " + std::to_string(epoxy_gl_version() / 10) + "." +
                std::to_string(epoxy_gl_version() % 10) +
                ((profile & GL_CONTEXT_CORE_PROFILE_BIT) ? " core" : " (not core)") +
                "; penumbra needs 4.5 core (" + currentDescription() + ")");
  }
  if (errors == GlErrors::Report) routeDebugMessages();
  tErrors = errors;
}

CurrentContext::~CurrentContext() {
  tErrors = previous_;
}

std::string CurrentContext::description() const {
  return currentDescription();
}

void checkErrors(const char* where) {
  if (tErrors == GlErrors::LeaveToHost) return;
  std::string errors;
  for (GLenum e = glGetError(); e != GL_NO_ERROR; e = glGetError()) {
    errors += "GL error 0x" + [e] {
      char hex[16];
      std::snprintf(hex, sizeof hex, "%04x", e);
      return std::string(hex);
    }() + "\n";
  }
  {
    std::lock_guard lock(gDebugMutex);
    errors += gDebugErrors;
    gDebugErrors.clear();
  }
  if (!errors.empty()) throw Error(std::string(where) + ": " + errors);
}

void discardPendingErrors() {
  if (tErrors == GlErrors::LeaveToHost) return;
  while (glGetError() != GL_NO_ERROR) {
  }
  std::lock_guard lock(gDebugMutex);
  gDebugErrors.clear();
}

}  // namespace penumbra::gl
