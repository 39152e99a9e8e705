#include "ibfvs/gl/window.h"

#include <cstdlib>
#include <utility>

#include <epoxy/gl.h>
// GLFW after epoxy, and without its own GL header.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "ibfvs/core/support/error.h"
#include "ibfvs/gl/context.h"

namespace ibfvs::gl {
namespace {

std::string g_last_error;

void on_glfw_error(int /*code*/, const char* description) {
  g_last_error = description;
}

}  // namespace

bool display_available() {
  const char* x = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  return (x && *x) || (wayland && *wayland);
}

WindowContext::WindowContext(int width, int height, const std::string& title, bool vsync) {
  glfwSetErrorCallback(on_glfw_error);
  if (!glfwInit()) throw GraphicsError("cannot start GLFW: " + g_last_error);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (!window_) {
    const std::string why = g_last_error;
    glfwTerminate();
    throw GraphicsError("cannot open a window with an OpenGL 4.5 core context: " + why);
  }
  glfwMakeContextCurrent(window_);
  keep_drivers_loaded();
  glfwSwapInterval(vsync ? 1 : 0);
}

WindowContext::~WindowContext() {
  if (window_) {
    glfwDestroyWindow(window_);
    glfwTerminate();
  }
}

WindowContext::WindowContext(WindowContext&& other) noexcept
    : window_(std::exchange(other.window_, nullptr)) {}

WindowContext& WindowContext::operator=(WindowContext&& other) noexcept {
  if (this != &other) {
    if (window_) {
      glfwDestroyWindow(window_);
      glfwTerminate();
    }
    window_ = std::exchange(other.window_, nullptr);
  }
  return *this;
}

bool WindowContext::should_close() const {
  return glfwWindowShouldClose(window_) != 0;
}

void WindowContext::request_close() {
  glfwSetWindowShouldClose(window_, GLFW_TRUE);
}

void WindowContext::set_title(const std::string& title) {
  glfwSetWindowTitle(window_, title.c_str());
}

void WindowContext::framebuffer_size(int& width, int& height) const {
  glfwGetFramebufferSize(window_, &width, &height);
}

void WindowContext::swap_buffers() {
  glfwSwapBuffers(window_);
}

ImageU8 WindowContext::read_pixels() const {
  int w = 0, h = 0;
  framebuffer_size(w, h);
  ImageU8 image(w, h, 4);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, image.pixels.data());
  return image;
}

void WindowContext::poll_events() {
  glfwPollEvents();
}

std::string WindowContext::renderer() const {
  const auto* r = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const auto* v = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  return std::string(r ? r : "?") + " | OpenGL " + (v ? v : "?");
}

}  // namespace ibfvs::gl
