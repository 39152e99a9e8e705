#include "ibfvs/core/support/isolation.h"

#include <fcntl.h>
#include <poll.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <climits>
#include <csignal>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <new>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "ibfvs/core/support/error.h"
#include "ibfvs/core/support/limits.h"

namespace ibfvs {
namespace {

// What the child writes first: how its work ended.
enum class Outcome : char {
  Ok = 'O',
  InputError = 'E',
  OutOfMemory = 'M',
  Other = 'X',
  Died = 'D'  // then the last words, and the child ends by its signal
};

// What the child last reported (last_words), for its fatal-signal handler:
// a fixed buffer, since the handler may only write what is already there.
char g_last_words[512];
std::size_t g_last_words_size = 0;

// The child's data segment and private writable mappings now (VmData), which
// RLIMIT_DATA counts; the limit is set above it, so that only what the work
// allocates counts (a sanitizer's shadow memory, mapped at start, does not).
std::uint64_t data_bytes() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmData:", 0) == 0) {
      std::istringstream in(line.substr(7));
      std::uint64_t kib = 0;
      in >> kib;
      return kib * 1024;
    }
  return 0;
}

bool write_all(int fd, const char* data, std::size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    data += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

int g_result_fd = -1;  // the child's result file, for on_terminate

// Empties the result buffer (a part of the result may be there) for what
// the child says instead; only calls that a signal handler may make.
bool restart_result() {
  return ::ftruncate(g_result_fd, 0) == 0 && ::lseek(g_result_fd, 0, SEEK_SET) == 0;
}

// A reader that lets an allocation failure escape through a function that
// may not throw (std::terminate): that is the memory limit, said as such.
[[noreturn]] void on_terminate() {
  try {
    if (const std::exception_ptr e = std::current_exception()) std::rethrow_exception(e);
  } catch (const std::bad_alloc&) {
    const char tag = static_cast<char>(Outcome::OutOfMemory);
    if (restart_result() && ::write(g_result_fd, &tag, 1) == 1) ::_exit(0);
  } catch (...) {
  }
  std::abort();
}

void on_fatal_signal(int sig) {
  char tag = static_cast<char>(Outcome::Died);
  if (restart_result() && ::write(g_result_fd, &tag, 1) == 1 && g_last_words_size > 0) {
    [[maybe_unused]] const ssize_t n = ::write(g_result_fd, g_last_words, g_last_words_size);
  }
  ::raise(sig);  // the handler was reset: the child ends by this signal
}

[[noreturn]] void run_child(int fd, const std::function<void(ByteWriter&)>& work,
                            const IsolationLimits& limits) {
  g_result_fd = fd;
  std::set_terminate(on_terminate);
  // A crash ends the child quietly, by its signal, for the parent to report:
  // no sanitizer's or fuzzer's handler, no core file.
  struct sigaction fatal {};
  fatal.sa_handler = on_fatal_signal;
  fatal.sa_flags = static_cast<int>(SA_RESETHAND | SA_NODEFER);
  sigemptyset(&fatal.sa_mask);
  for (const int s : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT}) ::sigaction(s, &fatal, nullptr);
  for (const int s : {SIGTRAP, SIGSYS, SIGXCPU}) std::signal(s, SIG_DFL);
  std::signal(SIGPIPE, SIG_IGN);
  const rlimit no_core{0, 0};
  setrlimit(RLIMIT_CORE, &no_core);
  // The reader's own complaints reach the user as the error line; its
  // standard error only with IBFVS_READER_STDERR (for debugging a reader).
  if (!std::getenv("IBFVS_READER_STDERR")) {
    const int null = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
    if (null >= 0) ::dup2(null, STDERR_FILENO);
  }
  if (limits.memory_bytes > 0) {
    const rlim_t cap = data_bytes() + limits.memory_bytes;
    const rlimit memory{cap, cap};
    setrlimit(RLIMIT_DATA, &memory);
  }
  if (limits.cpu_seconds > 0) {
    const rlimit cpu{limits.cpu_seconds, limits.cpu_seconds + 5};
    setrlimit(RLIMIT_CPU, &cpu);
  }
  // The result goes straight into the buffer after its tag; on a failure
  // the buffer is emptied and says what went wrong instead.
  Outcome outcome = Outcome::Ok;
  std::string message;
  const char ok_tag = static_cast<char>(Outcome::Ok);
  try {
    if (!write_all(fd, &ok_tag, 1)) ::_exit(3);
    ByteWriter out(fd);
    work(out);
    out.flush();
  } catch (const InputError& e) {
    outcome = Outcome::InputError;
    message = e.what();
  } catch (const std::bad_alloc&) {
    outcome = Outcome::OutOfMemory;
  } catch (const std::exception& e) {
    outcome = Outcome::Other;
    message = e.what();
  } catch (...) {
    outcome = Outcome::Other;
    message = "an unknown error";
  }
  if (outcome != Outcome::Ok) {
    const char tag = static_cast<char>(outcome);
    if (!restart_result() || !write_all(fd, &tag, 1) ||
        !write_all(fd, message.data(), message.size()))
      ::_exit(3);
  }
  ::_exit(0);
}

std::string signal_name(int sig) {
  const char* abbrev = sigabbrev_np(sig);
  return abbrev ? std::string("SIG") + abbrev : "signal " + std::to_string(sig);
}

// The child's buffer, mapped (empty: nothing written).
IsolatedBytes map_back(int fd) {
  struct stat st {};
  if (::fstat(fd, &st) != 0 || st.st_size <= 0) return {};
  const auto size = static_cast<std::size_t>(st.st_size);
  void* p = ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE, fd, 0);
  if (p == MAP_FAILED) throw std::bad_alloc();
  return IsolatedBytes(static_cast<const char*>(p), size, 0);
}

class Fd {
 public:
  explicit Fd(int fd) : fd_(fd) {}
  ~Fd() {
    if (fd_ >= 0) ::close(fd_);
  }
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  [[nodiscard]] int get() const { return fd_; }

 private:
  int fd_;
};

// Waits for the child to end, into `status`; after `seconds` of wall-clock
// time (0: no limit) kills it first. True when it was killed for time.
bool wait_for(pid_t pid, unsigned seconds, const std::string& subject, int& status) {
  bool killed = false;
  if (seconds > 0) {
    using Clock = std::chrono::steady_clock;
    const auto deadline = Clock::now() + std::chrono::seconds(seconds);
    const auto left_ms = [&] {
      return std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
    };
    // The child's end as a file descriptor to poll (Linux 5.3); without
    // one, a poll of waitpid every few milliseconds.
    const Fd ended(static_cast<int>(::syscall(SYS_pidfd_open, pid, 0)));
    for (long long pause_us = 50;;) {
      const long long left = left_ms();
      if (left <= 0) {
        ::kill(pid, SIGKILL);
        killed = true;
        break;
      }
      if (ended.get() >= 0) {
        pollfd p{ended.get(), POLLIN, 0};
        const int r = ::poll(&p, 1, static_cast<int>(std::min<long long>(left, INT_MAX)));
        if (r > 0 || (r < 0 && errno != EINTR)) break;
      } else {
        const pid_t done = ::waitpid(pid, &status, WNOHANG);
        if (done == pid) return false;
        if (done < 0 && errno != EINTR) break;
        ::usleep(static_cast<useconds_t>(std::min(pause_us, left * 1000)));
        pause_us = std::min<long long>(pause_us * 2, 10000);
      }
    }
  }
  while (::waitpid(pid, &status, 0) < 0)
    if (errno != EINTR)
      throw InputError(subject + ": lost the process reading it (" + std::strerror(errno) + ")");
  return killed;
}

}  // namespace

void last_words(std::string_view text) {
  const std::size_t n = std::min(text.size(), sizeof g_last_words);
  g_last_words_size = 0;
  std::memcpy(g_last_words, text.data(), n);
  g_last_words_size = n;
}

unsigned reader_seconds() {
  if (const char* text = std::getenv("IBFVS_READER_SECONDS"); text && *text) {
    char* end = nullptr;
    const unsigned long v = std::strtoul(text, &end, 10);
    if (end && *end == '\0' && v >= 1 && v <= 1000000) return static_cast<unsigned>(v);
  }
  return 60;
}

IsolationLimits reader_limits() {
  IsolationLimits limits;
  limits.memory_bytes = memory_limit() / 2;
  limits.cpu_seconds = reader_seconds();
  limits.wall_seconds = reader_seconds();
  return limits;
}

IsolatedBytes::IsolatedBytes(const char* data, std::size_t size, std::size_t skip)
    : data_(data), size_(size), skip_(std::min(skip, size)) {}

IsolatedBytes::~IsolatedBytes() {
  if (data_) ::munmap(const_cast<char*>(data_), size_);
}

IsolatedBytes::IsolatedBytes(IsolatedBytes&& other) noexcept
    : data_(std::exchange(other.data_, nullptr)),
      size_(std::exchange(other.size_, 0)),
      skip_(std::exchange(other.skip_, 0)) {}

IsolatedBytes IsolatedBytes::after(std::size_t n) && {
  IsolatedBytes out(std::move(*this));
  out.skip_ = std::min(out.skip_ + n, out.size_);
  return out;
}

IsolatedBytes& IsolatedBytes::operator=(IsolatedBytes&& other) noexcept {
  if (this != &other) {
    if (data_) ::munmap(const_cast<char*>(data_), size_);
    data_ = std::exchange(other.data_, nullptr);
    size_ = std::exchange(other.size_, 0);
    skip_ = std::exchange(other.skip_, 0);
  }
  return *this;
}

IsolatedBytes run_isolated(const std::string& subject, const std::string& who,
                           const std::function<void(ByteWriter&)>& work,
                           const IsolationLimits& limits) {
  const Fd result(::memfd_create("ibfvs-isolated", MFD_CLOEXEC));
  if (result.get() < 0)
    throw InputError(subject + ": cannot make a buffer to read it in (" + std::strerror(errno) +
                     ")");
  const pid_t pid = ::fork();
  if (pid < 0)
    throw InputError(subject + ": cannot start a process to read it in (" + std::strerror(errno) +
                     ")");
  if (pid == 0) run_child(result.get(), work, limits);
  int status = 0;
  const bool out_of_time = wait_for(pid, limits.wall_seconds, subject, status);
  const auto ran_too_long = [&](unsigned seconds, const char* what) {
    return InputError(subject + ": " + who + " ran for more than " + std::to_string(seconds) +
                      " s of " + what + " on it and was stopped (IBFVS_READER_SECONDS=" +
                      std::to_string(seconds * 10) + " gives it longer)");
  };
  if (out_of_time) throw ran_too_long(limits.wall_seconds, "wall-clock time");

  IsolatedBytes said = map_back(result.get());
  const std::string_view bytes = said.view();
  if (WIFSIGNALED(status)) {
    const int sig = WTERMSIG(status);
    const std::string last = bytes.size() > 1 && bytes[0] == static_cast<char>(Outcome::Died)
                                 ? std::string(bytes.substr(1))
                                 : std::string();
    if (sig == SIGXCPU) throw ran_too_long(limits.cpu_seconds, "CPU time");
    if (sig == SIGKILL)
      throw InputError(subject + ": " + who +
                       " was killed while reading it (SIGKILL: out of memory?)");
    throw InputError(one_line(subject + ": " + who + " crashed on it (" + signal_name(sig) + ")" +
                              (last.empty() ? ": the file is damaged, or not what its name says"
                                            : " after reporting: " + last)));
  }
  const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  if (code != 0 || bytes.empty())
    throw InputError(subject + ": " + who + " stopped on it without an answer (exit status " +
                     std::to_string(code) +
                     "; out of memory, or a failed check; IBFVS_READER_STDERR=1 shows its output)");
  const std::string payload(bytes.size() > 1 && bytes[0] != static_cast<char>(Outcome::Ok)
                                ? bytes.substr(1)
                                : std::string_view());
  switch (static_cast<Outcome>(bytes[0])) {
    case Outcome::Ok:
      return std::move(said).after(1);
    case Outcome::InputError:
      throw InputError(payload);
    case Outcome::OutOfMemory:
      throw InputError(subject + ": too large to read (it needs more than " +
                       format_bytes(static_cast<double>(limits.memory_bytes)) + " of memory)");
    case Outcome::Other:
      throw InputError(subject + ": " + payload);
    case Outcome::Died:  // only with a signal, above
      break;
  }
  throw InputError(subject + ": " + who + " gave an answer that cannot be read");
}

// ------------------------------------------------------------ bytes

void ByteWriter::append(const char* data, std::size_t size) {
  constexpr std::size_t kBuffer = 1 << 20;
  if (fd_ < 0 || size < kBuffer) {
    buffer_.append(data, size);
    if (fd_ >= 0 && buffer_.size() >= kBuffer) flush();
    return;
  }
  flush();  // a large array: from its own memory, not through the buffer
  if (!write_all(fd_, data, size)) throw std::runtime_error("cannot write the result");
}

void ByteWriter::flush() {
  if (fd_ < 0 || buffer_.empty()) return;
  if (!write_all(fd_, buffer_.data(), buffer_.size()))
    throw std::runtime_error("cannot write the result");
  buffer_.clear();
}

std::size_t ByteReader::count(std::size_t each) {
  const auto n = get<std::uint64_t>();
  if (each > 0 && n > (bytes_.size() - at_) / each)
    throw InputError(subject_ + ": a record cut short (" + std::to_string(n) + " items)");
  return static_cast<std::size_t>(n);
}

const char* ByteReader::take(std::size_t n) {
  if (n > bytes_.size() - at_) throw InputError(subject_ + ": a record cut short");
  const char* p = bytes_.data() + at_;
  at_ += n;
  return p;
}

}  // namespace ibfvs
