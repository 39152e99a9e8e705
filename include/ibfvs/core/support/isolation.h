#pragma once
// Untrusted files read where a crash cannot take the process down: the
// reading runs in a child process (fork) under a memory limit, and hands its
// result back as bytes. A crash, an allocation the limit refuses or a reader
// that runs away becomes one InputError naming the file, as a browser turns
// a crashed renderer into a message (STYLE.md, "Untrusted input"). The
// format's own library then does all the parsing: nothing in front of it
// re-parses the file, so nothing refuses what that library reads.
//
// Plus a small byte format (ByteWriter, ByteReader) for what the child hands
// back (a mesh in it: mesh/mesh_bytes.h).

#include <cstdint>
#include <cstring>
#include <functional>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace ibfvs {

/// What a child may use.
struct IsolationLimits {
  /// Bytes of memory the child may allocate beyond what it inherits (its
  /// data segment and private mappings, RLIMIT_DATA); 0: no limit.
  std::uint64_t memory_bytes = 0;
  /// CPU seconds (RLIMIT_CPU); 0: no limit.
  unsigned cpu_seconds = 0;
  /// Seconds of wall-clock time, after which the parent kills the child (a
  /// reader that waits, or loops in system calls); 0: no limit.
  unsigned wall_seconds = 0;
};

/// The limits for a file reader: half of memory_limit() (the machine's
/// memory, or IBFVS_MEMORY_LIMIT), and reader_seconds() of CPU and of
/// wall-clock time.
IsolationLimits reader_limits();

/// How long a reader may run on one file: 60 s, or IBFVS_READER_SECONDS
/// (a whole number, at least 1) for files that take longer. A reader that
/// loops stops after that, with one error line naming the file.
unsigned reader_seconds();

class ByteWriter;

/// What a child handed back: its bytes, mapped from the buffer it wrote
/// (no copy). Move-only.
class IsolatedBytes {
 public:
  IsolatedBytes() = default;
  IsolatedBytes(const char* data, std::size_t size, std::size_t skip);
  ~IsolatedBytes();
  IsolatedBytes(IsolatedBytes&& other) noexcept;
  IsolatedBytes& operator=(IsolatedBytes&& other) noexcept;
  IsolatedBytes(const IsolatedBytes&) = delete;
  IsolatedBytes& operator=(const IsolatedBytes&) = delete;
  [[nodiscard]] std::string_view view() const {
    return data_ ? std::string_view(data_ + skip_, size_ - skip_) : std::string_view();
  }
  /// The same bytes less the first n.
  [[nodiscard]] IsolatedBytes after(std::size_t n) &&;

 private:
  const char* data_ = nullptr;  // the mapping (null: nothing)
  std::size_t size_ = 0, skip_ = 0;
};

/// Runs `work` in a child process, which writes its result with the writer
/// it is given (straight into a shared buffer), and returns those bytes. The
/// child's InputError comes back as an InputError with the same message;
/// another exception as "SUBJECT: its message"; running out of memory as
/// "SUBJECT: too large to read (it needs more than N of memory)"; a crash
/// as "SUBJECT: WHO crashed on it (SIGSEGV)", with its last_words. `subject`
/// is what messages start with (the file), `who` what does the reading
/// ("VTK's reader"). Running past the CPU or wall-clock limit is "SUBJECT:
/// WHO ran for more than N s on it". The child never returns: it leaves by _exit, so
/// neither atexit handlers nor the parent's buffered output run twice. The
/// calling thread must hold no lock the work takes (the child has only that
/// thread; a lock another thread held at the fork stays held there).
IsolatedBytes run_isolated(const std::string& subject, const std::string& who,
                           const std::function<void(ByteWriter&)>& work,
                           const IsolationLimits& limits = reader_limits());

/// What a child says before it may die: the reader's last complaint (VTK's
/// "Unable to allocate ..." before it aborts). If the child then crashes,
/// the parent's error line ends with it. Keeps the first 512 bytes; cheap
/// (a copy), and harmless outside a child.
void last_words(std::string_view text);

/// Appends values to a byte string, or writes them to a file descriptor
/// (buffered; large arrays straight from their memory). Host byte order:
/// the reader is this program's own child.
class ByteWriter {
 public:
  ByteWriter() = default;  ///< into a string: take()
  explicit ByteWriter(int fd) : fd_(fd) {}
  ~ByteWriter() = default;
  ByteWriter(const ByteWriter&) = delete;
  ByteWriter& operator=(const ByteWriter&) = delete;

  template <class T>
  requires std::is_trivially_copyable_v<T>
  void put(const T& value) { append(reinterpret_cast<const char*>(&value), sizeof value); }
  template <class T>
  requires std::is_trivially_copyable_v<T>
  void put(const std::vector<T>& values) {
    put<std::uint64_t>(values.size());
    append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
  }
  void put(const std::string& text) {
    put<std::uint64_t>(text.size());
    append(text.data(), text.size());
  }
  void put(const std::vector<std::string>& texts) {
    put<std::uint64_t>(texts.size());
    for (const std::string& t : texts) put(t);
  }
  /// Writes what is buffered (to the file); throws std::runtime_error when
  /// the file cannot take it.
  void flush();
  /// The bytes (string mode).
  std::string take() { return std::move(buffer_); }

 private:
  void append(const char* data, std::size_t size);
  int fd_ = -1;
  std::string buffer_;
};

/// Reads what a ByteWriter wrote, checking every length against what is
/// left; throws InputError "SUBJECT: ..." on a short or inconsistent record.
class ByteReader {
 public:
  ByteReader(std::string_view bytes, std::string subject)
      : bytes_(bytes), subject_(std::move(subject)) {}
  template <class T>
  requires std::is_trivially_copyable_v<T> T get() {
    T value;
    std::memcpy(&value, take(sizeof value), sizeof value);
    return value;
  }
  template <class T>
  requires std::is_trivially_copyable_v<T> std::vector<T> get_vector() {
    const auto n = count(sizeof(T));
    std::vector<T> values(n);
    if (n > 0) std::memcpy(values.data(), take(n * sizeof(T)), n * sizeof(T));
    return values;
  }
  std::string get_string() {
    const auto n = count(1);
    return std::string(take(n), n);
  }
  std::vector<std::string> get_strings() {
    std::vector<std::string> texts(count(sizeof(std::uint64_t)));
    for (std::string& t : texts) t = get_string();
    return texts;
  }
  [[nodiscard]] bool done() const { return at_ == bytes_.size(); }

 private:
  std::size_t count(std::size_t each);
  const char* take(std::size_t n);
  std::string_view bytes_;
  std::size_t at_ = 0;
  std::string subject_;
};

}  // namespace ibfvs
