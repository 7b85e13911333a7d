// The viewer's window: GLFW 3.3 with an OpenGL 4.5 core context, and Dear ImGui on top of it
// (its GLFW and OpenGL3 backends). Owns both for its lifetime.
#pragma once

#include <cstdint>
#include <vector>

struct GLFWwindow;

namespace penumbra::viewer {

class ViewerWindow {
 public:
  // Opens the window and makes its context current; throws Error when there is no display or no
  // GL 4.5 core context (the message says which, and how to run under xvfb-run).
  ViewerWindow(int width, int height, const char* title);
  ~ViewerWindow();
  ViewerWindow(const ViewerWindow&) = delete;
  ViewerWindow& operator=(const ViewerWindow&) = delete;

  bool shouldClose() const;
  // Takes the pending events (waiting up to `waitSeconds` for one when > 0: an idle window then
  // sleeps instead of spinning a core) and starts an ImGui frame.
  void beginFrame(double waitSeconds = 0.0);
  // Draws ImGui's draw lists over what is in the back buffer.
  void drawUi();
  void swapBuffers();
  // The back buffer as 8-bit RGB, row 0 at the top (call before swapBuffers).
  std::vector<uint8_t> readBackBuffer(int& width, int& height) const;
  void framebufferSize(int& width, int& height) const;
  // The keys pressed since the last call (GLFW key codes), when ImGui does not want the keyboard.
  // Taken from GLFW's callback rather than ImGui 1.86's key state, which misses a press and
  // release that fall between two frames (a quick tap while a slow frame renders).
  std::vector<int> takeKeyPresses();
  GLFWwindow* handle() const { return window_; }

 private:
  GLFWwindow* window_ = nullptr;
  std::vector<int> keyPresses_;
  friend void onKey(GLFWwindow*, int, int, int, int);
};

}  // namespace penumbra::viewer
