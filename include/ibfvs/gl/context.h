#pragma once
// The one place that creates OpenGL contexts. Headless: EGL without a display
// server, on the NVIDIA EGL device when there is one, else on Mesa (llvmpipe
// through EGL_MESA_platform_surfaceless). OpenGL 4.5 core profile.

#include <memory>
#include <string>
#include <vector>

namespace ibfvs::gl {

/// Options for a headless context.
struct ContextOptions {
  /// Record KHR_debug errors; throw_if_errors() turns them into exceptions.
  /// Defaults to on in debug builds (and with IBFVS_GL_DEBUG=1 in the environment).
  bool debug = default_debug();
  static bool default_debug();
};

/// An OpenGL 4.5 core context, current on the creating thread, with no
/// default framebuffer (render into framebuffer objects). Move-only.
class HeadlessContext {
 public:
  /// Throws GraphicsError when no EGL display or GL 4.5 context can be made;
  /// the message lists what was tried.
  explicit HeadlessContext(const ContextOptions& options = {});
  ~HeadlessContext();
  HeadlessContext(HeadlessContext&&) noexcept;
  HeadlessContext& operator=(HeadlessContext&&) noexcept;
  HeadlessContext(const HeadlessContext&) = delete;
  HeadlessContext& operator=(const HeadlessContext&) = delete;

  void make_current();
  /// Makes no context current on this thread (so that another thread may
  /// make this one current).
  void release_current();
  /// "Mesa llvmpipe (LLVM 15.0.6, 256 bits) | OpenGL 4.5 (Core Profile) ..."
  [[nodiscard]] std::string renderer() const;
  /// Which EGL platform: "device" or "surfaceless".
  [[nodiscard]] const std::string& platform() const;

  /// Throws GraphicsError listing the GL errors recorded since the last call
  /// (only records with debug on). Cheap when there are none.
  void throw_if_errors();

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

/// Process settings that make Mesa's llvmpipe fast, for a process that
/// renders (the command, the Python module); call before the first context.
/// Freed memory is kept for reuse instead of being trimmed back to the kernel
/// (llvmpipe frees and reallocates large buffers every frame: a quarter of
/// the time went to page faults, 3x slower on the 75K-triangle bunny), and
/// on two cores llvmpipe gets a third rasteriser thread, which keeps both
/// busy (the subdivided cow at 512x512: 150-180 -> 190-205 fps); the user's
/// LP_NUM_THREADS wins and GPU drivers ignore it.
void tune_process_for_rendering();

/// The OpenGL version of the context current on this thread (a host's:
/// VTK's or ParaView's render window, through EGL or GLX) as 10 major +
/// minor, 45 for 4.5; 0 where none is current. Throws GraphicsError where
/// OpenGL's own library (libOpenGL.so.0 or libGL.so.1, which libepoxy loads
/// its first functions from) is not installed, as HeadlessContext does.
int current_gl_version();
/// The context current on this thread (an EGL or a GLX context's handle),
/// null where none is: to tell whether the one objects were made in is.
const void* current_context();

/// Errors recorded by the KHR_debug callback of the current thread's context.
std::vector<std::string> take_recorded_gl_errors();

/// Keeps the GL drivers loaded so far (Mesa's *_dri.so) loaded until the
/// process ends, so that LeakSanitizer can name them in what they leak
/// (tests/lsan.supp) instead of an unloaded, unknown module. Both context
/// kinds call it once their context exists.
void keep_drivers_loaded();

}  // namespace ibfvs::gl
