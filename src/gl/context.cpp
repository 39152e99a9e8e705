#include "ibfvs/gl/context.h"

#include <dlfcn.h>
#include <link.h>
#include <malloc.h>
#include <stdlib.h>

#include <cstdlib>
#include <cstring>
#include <map>
#include <mutex>
#include <sstream>
#include <thread>

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include "ibfvs/core/support/error.h"

namespace ibfvs::gl {
namespace {

// The KHR_debug callback runs inside the driver's call stack, where throwing
// is undefined; it records, and throw_if_errors() throws later.
thread_local std::vector<std::string> g_errors;

void GLAPIENTRY on_debug_message(GLenum /*source*/, GLenum type, GLuint /*id*/, GLenum severity,
                                 GLsizei length, const GLchar* message, const void* /*user*/) {
  if (type == GL_DEBUG_TYPE_ERROR || severity == GL_DEBUG_SEVERITY_HIGH)
    g_errors.emplace_back(message, static_cast<std::size_t>(length));
}

bool has_extension(const char* list, const char* name) {
  if (!list) return false;
  const std::size_t n = std::strlen(name);
  for (const char* p = list; (p = std::strstr(p, name)); p += n)
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  return false;
}

}  // namespace

void keep_drivers_loaded() {
  dl_iterate_phdr(
      [](dl_phdr_info* info, std::size_t, void*) {
        if (info->dlpi_name && std::strstr(info->dlpi_name, "_dri.so"))
          dlopen(info->dlpi_name, RTLD_NOW | RTLD_NOLOAD | RTLD_NODELETE);
        return 0;
      },
      nullptr);
}

bool ContextOptions::default_debug() {
  if (const char* env = std::getenv("IBFVS_GL_DEBUG")) return std::strcmp(env, "0") != 0;
#ifdef IBFVS_GL_DEBUG_DEFAULT
  return true;
#else
  return false;
#endif
}

namespace {

// EGL displays are one per process and device: terminating one destroys
// every context on it. Contexts count their display's users and terminate it
// with the last.
std::mutex& display_mutex() {
  static std::mutex m;
  return m;
}
std::map<EGLDisplay, int>& display_users() {
  static std::map<EGLDisplay, int> users;
  return users;
}
void retain_display(EGLDisplay d) {
  const std::lock_guard lock(display_mutex());
  ++display_users()[d];
}
// Terminates the display when no context uses it (a failed try on a display
// that others use leaves it alone).
void release_display(EGLDisplay d, bool retained) {
  const std::lock_guard lock(display_mutex());
  auto& users = display_users();
  const auto it = users.find(d);
  if (retained && it != users.end() && --it->second > 0) return;
  if (!retained && it != users.end()) return;
  if (it != users.end()) users.erase(it);
  eglTerminate(d);
}

}  // namespace

struct HeadlessContext::Impl {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  std::string platform;
  bool debug = false;

  ~Impl() {
    if (display != EGL_NO_DISPLAY) {
      eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      if (context != EGL_NO_CONTEXT) eglDestroyContext(display, context);
      release_display(display, true);
    }
  }

  // Tries one display; on success leaves display/context set and current.
  bool try_display(EGLDisplay dpy, const std::string& name, std::ostringstream& log) {
    EGLint major = 0, minor = 0;
    if (dpy == EGL_NO_DISPLAY || !eglInitialize(dpy, &major, &minor)) {
      log << name << ": eglInitialize failed; ";
      return false;
    }
    keep_drivers_loaded();
    if (!eglBindAPI(EGL_OPENGL_API)) {
      log << name << ": no desktop OpenGL API; ";
      release_display(dpy, false);
      return false;
    }
    const EGLint config_attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    EGLConfig config = nullptr;
    EGLint count = 0;
    const bool no_config =
        has_extension(eglQueryString(dpy, EGL_EXTENSIONS), "EGL_KHR_no_config_context");
    if (!no_config && (!eglChooseConfig(dpy, config_attribs, &config, 1, &count) || count == 0)) {
      log << name << ": no OpenGL config; ";
      release_display(dpy, false);
      return false;
    }
    const EGLint ctx_attribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                  4,
                                  EGL_CONTEXT_MINOR_VERSION,
                                  5,
                                  EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                  EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                  EGL_CONTEXT_OPENGL_DEBUG,
                                  debug ? EGL_TRUE : EGL_FALSE,
                                  EGL_NONE};
    EGLContext ctx =
        eglCreateContext(dpy, no_config ? EGL_NO_CONFIG_KHR : config, EGL_NO_CONTEXT, ctx_attribs);
    if (ctx == EGL_NO_CONTEXT) {
      log << name << ": no OpenGL 4.5 core context (EGL error 0x" << std::hex << eglGetError()
          << std::dec << "); ";
      release_display(dpy, false);
      return false;
    }
    if (!eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) {
      log << name << ": cannot make the context current without a surface; ";
      eglDestroyContext(dpy, ctx);
      release_display(dpy, false);
      return false;
    }
    display = dpy;
    context = ctx;
    platform = name;
    retain_display(dpy);
    return true;
  }
};

// libepoxy finds OpenGL 1.0 and 1.1's functions in OpenGL's own library
// (GLVND's libOpenGL.so.0, or libGL.so.1), not through EGL, and aborts the
// process where neither is installed (an EGL-only system): asked first, that
// is one error that says what to install.
namespace {
void require_gl_library() {
  static const bool found = [] {
    for (const char* lib : {"libOpenGL.so.0", "libGL.so.1"})
      if (void* handle = dlopen(lib, RTLD_LAZY | RTLD_LOCAL)) {
        dlclose(handle);
        return true;
      }
    return false;
  }();
  if (!found)
    throw GraphicsError(
        "OpenGL's library is not installed (neither libOpenGL.so.0 nor libGL.so.1): "
        "apt-get install libopengl0 (or libgl1), or your system's OpenGL (GLVND) package");
}
}  // namespace

HeadlessContext::HeadlessContext(const ContextOptions& options) : impl_(std::make_unique<Impl>()) {
  require_gl_library();
  impl_->debug = options.debug;
  std::ostringstream log;
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (!client) throw GraphicsError("EGL: no client extensions (is libEGL installed?)");
  bool ok = false;
  const char* forced = std::getenv("IBFVS_EGL_PLATFORM");  // "device" or "surfaceless"
  // Prefer a hardware EGL device (NVIDIA headless); Mesa's software device is
  // reached through the surfaceless platform below.
  if (!ok && (!forced || std::strcmp(forced, "device") == 0) &&
      has_extension(client, "EGL_EXT_device_enumeration") &&
      has_extension(client, "EGL_EXT_platform_device")) {
    EGLDeviceEXT devices[16];
    EGLint n = 0;
    if (eglQueryDevicesEXT(16, devices, &n)) {
      for (EGLint i = 0; i < n && !ok; ++i) {
        const char* dev_ext = eglQueryDeviceStringEXT(devices[i], EGL_EXTENSIONS);
        if (!forced && has_extension(dev_ext, "EGL_MESA_device_software")) continue;
        ok = impl_->try_display(
            eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr), "device", log);
      }
    }
  }
  if (!ok && (!forced || std::strcmp(forced, "surfaceless") == 0) &&
      has_extension(client, "EGL_MESA_platform_surfaceless")) {
    ok = impl_->try_display(
        eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr),
        "surfaceless", log);
  }
  if (!ok)
    throw GraphicsError("cannot create a headless OpenGL 4.5 context through EGL: " + log.str() +
                        "install Mesa (libegl-mesa0, libgl1-mesa-dri) or a GPU driver");
  if (epoxy_gl_version() < 45) throw GraphicsError("OpenGL 4.5 is required, got " + renderer());
  if (options.debug && epoxy_has_gl_extension("GL_KHR_debug")) {
    glEnable(GL_DEBUG_OUTPUT);
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    glDebugMessageCallback(on_debug_message, nullptr);
    glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DONT_CARE, 0, nullptr, GL_TRUE);
  }
}

HeadlessContext::~HeadlessContext() = default;
HeadlessContext::HeadlessContext(HeadlessContext&&) noexcept = default;
HeadlessContext& HeadlessContext::operator=(HeadlessContext&&) noexcept = default;

void HeadlessContext::make_current() {
  if (!eglMakeCurrent(impl_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, impl_->context))
    throw GraphicsError("EGL: cannot make the context current");
}

void tune_process_for_rendering() {
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
  if (std::thread::hardware_concurrency() == 2) setenv("LP_NUM_THREADS", "3", 0);
}

const void* current_context() {
  if (const EGLContext egl = eglGetCurrentContext(); egl != EGL_NO_CONTEXT) return egl;
  // A GLX context (a host's X window) can be current only where the process
  // has loaded GLX: asked without loading it.
  const void* glx = nullptr;
  for (const char* lib : {"libGLX.so.0", "libGL.so.1"}) {
    if (glx) break;
    if (void* handle = dlopen(lib, RTLD_LAZY | RTLD_NOLOAD)) {
      using GetCurrent = void* (*)();
      if (auto get = reinterpret_cast<GetCurrent>(dlsym(handle, "glXGetCurrentContext")))
        glx = get();
      dlclose(handle);
    }
  }
  return glx;
}

int current_gl_version() {
  if (!current_context()) return 0;
  require_gl_library();
  return epoxy_gl_version();
}

void HeadlessContext::release_current() {
  eglMakeCurrent(impl_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
}

std::string HeadlessContext::renderer() const {
  const auto str = [](GLenum name) {
    const auto* s = reinterpret_cast<const char*>(glGetString(name));
    return std::string(s ? s : "?");
  };
  return str(GL_RENDERER) + " | OpenGL " + str(GL_VERSION) + " | " + str(GL_VENDOR);
}

const std::string& HeadlessContext::platform() const {
  return impl_->platform;
}

void HeadlessContext::throw_if_errors() {
  std::vector<std::string> errors = take_recorded_gl_errors();
  // Without KHR_debug output, fall back to glGetError.
  if (!impl_->debug)
    for (GLenum e; (e = glGetError()) != GL_NO_ERROR;) {
      std::ostringstream s;
      s << "glGetError 0x" << std::hex << e;
      errors.push_back(s.str());
    }
  if (errors.empty()) return;
  std::string msg = "OpenGL error: " + errors.front();
  if (errors.size() > 1) msg += " (and " + std::to_string(errors.size() - 1) + " more)";
  throw GraphicsError(msg);
}

std::vector<std::string> take_recorded_gl_errors() {
  std::vector<std::string> out;
  out.swap(g_errors);
  return out;
}

}  // namespace ibfvs::gl
