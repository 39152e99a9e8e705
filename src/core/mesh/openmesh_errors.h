#pragma once
// Internal to the core: OpenMesh's error stream, captured.

#include <iostream>
#include <mutex>
#include <sstream>
#include <streambuf>
#include <string>
#include <vector>

#include <OpenMesh/Core/System/omstream.hh>

// LeakSanitizer's interface, where the build has it.
#if defined(__SANITIZE_ADDRESS__)
#define IBFVS_LSAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define IBFVS_LSAN 1
#endif
#endif
#ifdef IBFVS_LSAN
#include <sanitizer/lsan_interface.h>
#endif

namespace ibfvs {

namespace detail {

// Where omerr writes: into the capture under way on this thread, else to
// standard error. Connected to omerr once, for the life of the process:
// OpenMesh's multiplexer forgets a target on disconnect without deleting it,
// so connecting and disconnecting per read leaked (LeakSanitizer, fuzzing).
class OmErrRouter : public std::streambuf {
 public:
  static OmErrRouter& instance() {
    static OmErrRouter router;
    static std::ostream stream(&router);
    static const bool connected = [] {
    // omerr() makes its standard-error target on first use, and
    // disconnect() drops it without deleting it: 16 bytes, once per
    // process, that OpenMesh gives no way to free.
#ifdef IBFVS_LSAN
      __lsan_disable();
#endif
      omerr().disconnect(std::cerr);
#ifdef IBFVS_LSAN
      __lsan_enable();
#endif
      omerr().connect(stream);
      return true;
    }();
    (void)connected;
    return router;
  }
  // The capture of this thread (nullptr: none).
  static std::ostringstream*& target() {
    thread_local std::ostringstream* current = nullptr;
    return current;
  }

 protected:
  int overflow(int c) override {
    if (c == traits_type::eof()) return traits_type::not_eof(c);
    const char ch = static_cast<char>(c);
    xsputn(&ch, 1);
    return c;
  }
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    if (std::ostringstream* t = target()) {
      t->write(s, n);
    } else {
      std::lock_guard<std::mutex> lock(mutex_);
      std::cerr.write(s, n);
    }
    return n;
  }

 private:
  std::mutex mutex_;
};

}  // namespace detail

// OpenMesh reports problems on its global omerr stream and then carries on with
// what it could read. Capture those lines for the duration of one read, so they
// can be classified (fatal: an index out of range; repairable: a face with
// repeated vertices) instead of being lost on stderr.
class OmErrCapture {
 public:
  OmErrCapture() {
    detail::OmErrRouter::instance();
    previous_ = detail::OmErrRouter::target();
    detail::OmErrRouter::target() = &buffer_;
  }
  ~OmErrCapture() {
    omerr().flush();
    detail::OmErrRouter::target() = previous_;
  }
  OmErrCapture(const OmErrCapture&) = delete;
  OmErrCapture& operator=(const OmErrCapture&) = delete;
  std::vector<std::string> lines() {
    omerr().flush();
    std::vector<std::string> out;
    std::istringstream in(buffer_.str());
    for (std::string line; std::getline(in, line);)
      if (!line.empty()) out.push_back(line);
    return out;
  }

 private:
  std::ostringstream buffer_;
  std::ostringstream* previous_ = nullptr;
};

}  // namespace ibfvs
