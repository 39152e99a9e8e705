#pragma once
// An OpenGL 4.5 core context with a window on the screen (GLFW), for the
// interactive viewer. The renderer draws offscreen as always; the window
// shows its output (blit) with the user interface on top.

#include <string>

#include "ibfvs/core/image/image.h"

struct GLFWwindow;

namespace ibfvs::gl {

/// Whether a display server is named in the environment (DISPLAY or
/// WAYLAND_DISPLAY); without one no window can be opened.
bool display_available();

/// A GLFW window with an OpenGL 4.5 core context, current on the creating
/// thread. One at a time per process. Move-only.
class WindowContext {
 public:
  /// Throws GraphicsError (with GLFW's own message) when GLFW cannot start or
  /// no 4.5 core context can be made.
  WindowContext(int width, int height, const std::string& title, bool vsync);
  ~WindowContext();
  WindowContext(WindowContext&& other) noexcept;
  WindowContext& operator=(WindowContext&& other) noexcept;
  WindowContext(const WindowContext&) = delete;
  WindowContext& operator=(const WindowContext&) = delete;

  [[nodiscard]] GLFWwindow* handle() const { return window_; }
  [[nodiscard]] bool should_close() const;
  void request_close();
  void set_title(const std::string& title);
  /// Size of the default framebuffer in pixels.
  void framebuffer_size(int& width, int& height) const;
  void swap_buffers();
  /// What the window shows (its back buffer, before swap_buffers), RGBA, rows bottom-up.
  [[nodiscard]] ImageU8 read_pixels() const;
  static void poll_events();
  /// "llvmpipe (LLVM 15.0.6, 256 bits) | OpenGL 4.5 (Core Profile) Mesa 22.3.6"
  [[nodiscard]] std::string renderer() const;

 private:
  GLFWwindow* window_ = nullptr;
};

}  // namespace ibfvs::gl
