// GLFW window, GL 4.5 core context and ImGui backends.
#include "viewer_window.h"

#include <epoxy/gl.h>
// GLFW after epoxy: epoxy declares the GL API, GLFW must not include another GL header.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

#include <algorithm>
#include <string>

#include "penumbra/error.h"

namespace penumbra::viewer {
namespace {

std::string gGlfwError;  // GLFW reports errors through a callback; the constructor reads it

void onGlfwError(int, const char* description) {
  gGlfwError = description;
}

}  // namespace

void onKey(GLFWwindow* window, int key, int, int action, int) {
  auto* self = static_cast<ViewerWindow*>(glfwGetWindowUserPointer(window));
  if (action == GLFW_PRESS && self != nullptr) self->keyPresses_.push_back(key);
}

ViewerWindow::ViewerWindow(int width, int height, const char* title) {
  glfwSetErrorCallback(onGlfwError);
  if (!glfwInit()) {
    throw Error("cannot start GLFW (" + gGlfwError +
                "); the viewer needs a display: run it on a desktop, or under xvfb-run "
                "(Debian's xvfb) without one");
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, GLFW_TRUE);
  window_ = glfwCreateWindow(width, height, title, nullptr, nullptr);
  if (window_ == nullptr) {
    const std::string why = gGlfwError;
    glfwTerminate();
    throw Error("cannot open a " + std::to_string(width) + "x" + std::to_string(height) +
                " window with an OpenGL 4.5 core context (" + why + ")");
  }
  glfwMakeContextCurrent(window_);
  glfwSetWindowUserPointer(window_, this);
  // Before ImGui's backend installs its callbacks: it chains to this one.
  glfwSetKeyCallback(window_, onKey);
  // Scripted runs must not wait for vertical blank: Xvfb has none, desktops would cap the rate.
  glfwSwapInterval(0);
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // the layout is fixed; no imgui.ini in the user's folder
  ImGui::StyleColorsDark();
  ImGui_ImplGlfw_InitForOpenGL(window_, true);
  ImGui_ImplOpenGL3_Init("#version 450");
}

ViewerWindow::~ViewerWindow() {
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  glfwDestroyWindow(window_);
  glfwTerminate();
}

bool ViewerWindow::shouldClose() const {
  return glfwWindowShouldClose(window_) != 0;
}

void ViewerWindow::beginFrame(double waitSeconds) {
  if (waitSeconds > 0.0) {
    glfwWaitEventsTimeout(waitSeconds);
  } else {
    glfwPollEvents();
  }
  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
}

void ViewerWindow::drawUi() {
  ImGui::Render();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

void ViewerWindow::swapBuffers() {
  glfwSwapBuffers(window_);
}

std::vector<int> ViewerWindow::takeKeyPresses() {
  std::vector<int> keys;
  keys.swap(keyPresses_);
  if (ImGui::GetIO().WantCaptureKeyboard) keys.clear();  // typed into a text field
  return keys;
}

void ViewerWindow::framebufferSize(int& width, int& height) const {
  glfwGetFramebufferSize(window_, &width, &height);
}

std::vector<uint8_t> ViewerWindow::readBackBuffer(int& width, int& height) const {
  framebufferSize(width, height);
  std::vector<uint8_t> bottomUp(size_t(width) * size_t(height) * 3);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, bottomUp.data());
  std::vector<uint8_t> topDown(bottomUp.size());
  const size_t row = size_t(width) * 3;
  for (int y = 0; y < height; ++y) {
    std::copy_n(&bottomUp[size_t(height - 1 - y) * row], row, &topDown[size_t(y) * row]);
  }
  return topDown;
}

}  // namespace penumbra::viewer
