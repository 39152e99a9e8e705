// run_isolated: the child's result, its errors, its crashes and its memory
// limit, each as the one line a user sees; the byte format it answers in.
#include <gtest/gtest.h>

#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <new>
#include <string>
#include <vector>

#include "ibfvs/core/mesh/mesh_bytes.h"
#include "ibfvs/core/mesh/procedural.h"
#include "ibfvs/core/support/error.h"
#include "ibfvs/core/support/isolation.h"

namespace ibfvs {
namespace {

// The text a child writes.
std::function<void(ByteWriter&)> says(std::function<std::string()> text) {
  return [text = std::move(text)](ByteWriter& out) { out.put(text()); };
}

std::string result(const IsolatedBytes& bytes) {
  ByteReader in(bytes.view(), "f");
  std::string text = in.get_string();
  EXPECT_TRUE(in.done());
  return text;
}

std::string error_of(const std::function<std::string()>& work,
                     const IsolationLimits& limits = reader_limits()) {
  try {
    run_isolated("data/x.vtk", "the reader", says(work), limits);
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    EXPECT_EQ(what.rfind("data/x.vtk: ", 0), 0u) << what;
    return what;
  }
  ADD_FAILURE() << "no error";
  return {};
}

TEST(Isolation, TheChildsBytesComeBack) {
  std::string big(3 << 20, 'x');  // more than a pipe holds
  big[12345] = 'y';
  EXPECT_EQ(result(run_isolated("f", "r", says([&] { return big; }))), big);
  EXPECT_EQ(result(run_isolated("f", "r", says([] { return std::string(); }))), "");
  // A part written (large arrays straight from their memory), then a
  // failure: the error alone comes back, not the part written.
  try {
    run_isolated("data/x.vtk", "r", [&](ByteWriter& out) {
      out.put(big);
      out.put(std::vector<char>(4 << 20, 'z'));
      throw InputError("data/x.vtk: cut short");
    });
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "data/x.vtk: cut short");
  }
}

TEST(Isolation, ErrorsComeBackAsTheyWere) {
  EXPECT_EQ(error_of([]() -> std::string { throw InputError("data/x.vtk: bad header"); }),
            "data/x.vtk: bad header");
  EXPECT_EQ(error_of([]() -> std::string { throw std::runtime_error("odd"); }), "data/x.vtk: odd");
  EXPECT_NE(error_of([]() -> std::string { throw std::bad_alloc(); }).find("too large to read"),
            std::string::npos);
}

TEST(Isolation, ACrashIsOneLineNamingTheFileAndTheSignal) {
  const std::string segv = error_of([]() -> std::string {
    std::raise(SIGSEGV);
    return "unreached";
  });
  EXPECT_NE(segv.find("the reader crashed on it (SIGSEGV)"), std::string::npos) << segv;
  // What the reader said last comes with the crash.
  const std::string abrt = error_of([]() -> std::string {
    last_words("Unable to allocate 9000000000 elements");
    std::abort();
  });
  EXPECT_NE(abrt.find("crashed on it (SIGABRT) after reporting: Unable to allocate 9000000000"),
            std::string::npos)
      << abrt;
  // The parent goes on, and the next read works.
  EXPECT_EQ(result(run_isolated("f", "r", says([] { return std::string("ok"); }))), "ok");
}

TEST(Isolation, TheMemoryLimitRefusesWhatAFileAsksFor) {
  IsolationLimits small;
  small.memory_bytes = 64u << 20;
  const std::string what = error_of(
      [] {
        std::vector<char> huge(std::size_t{1} << 30, 1);  // 1 GiB, touched
        return std::string(1, huge[12345]);
      },
      small);
#if defined(__SANITIZE_ADDRESS__) || \
    defined(IBFVS_ASAN_RUNTIME)  // the runtime, built with it or not
  // AddressSanitizer reports the failed mapping itself and ends the child.
  EXPECT_TRUE(what.find("too large to read") != std::string::npos ||
              what.find("without an answer") != std::string::npos)
      << what;
#else
  EXPECT_NE(what.find("too large to read (it needs more than 64 MiB of memory)"), std::string::npos)
      << what;
#endif
  // Within the limit, the same work succeeds.
  small.memory_bytes = 2ull << 30;
  EXPECT_EQ(result(run_isolated("f", "r", says([] {
                                  std::vector<char> v(std::size_t{1} << 28, 1);
                                  return std::string(1, v[5]);
                                }),
                                small)),
            std::string(1, '\1'));
}

// A reader that never finishes stops at the limits: one that loops (CPU
// time), and one that waits without using any (wall-clock time).
TEST(Isolation, AReaderThatNeverFinishesIsStopped) {
  IsolationLimits quick;
  quick.cpu_seconds = 1;
  quick.wall_seconds = 30;
  const std::string loops = error_of(
      [] {
        volatile bool going = true;
        while (going) {
        }
        return std::string();
      },
      quick);
  EXPECT_NE(loops.find("the reader ran for more than 1 s of CPU time on it and was stopped"),
            std::string::npos)
      << loops;
  quick.cpu_seconds = 0;
  quick.wall_seconds = 1;
  const auto start = std::chrono::steady_clock::now();
  const std::string waits = error_of(
      [] {
        ::pause();
        return std::string();
      },
      quick);
  EXPECT_NE(waits.find("the reader ran for more than 1 s of wall-clock time on it"),
            std::string::npos)
      << waits;
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(10));
  // A quick child is not held back to the limit.
  const auto quick_start = std::chrono::steady_clock::now();
  EXPECT_EQ(result(run_isolated("f", "r", says([] { return std::string("ok"); }), quick)), "ok");
  EXPECT_LT(std::chrono::steady_clock::now() - quick_start, std::chrono::milliseconds(900));
}

TEST(Isolation, AReaderGetsAMinuteUnlessToldOtherwise) {
  ::unsetenv("IBFVS_READER_SECONDS");
  EXPECT_EQ(reader_limits().cpu_seconds, 60u);
  EXPECT_EQ(reader_limits().wall_seconds, 60u);
  ::setenv("IBFVS_READER_SECONDS", "600", 1);
  EXPECT_EQ(reader_limits().wall_seconds, 600u);
  ::setenv("IBFVS_READER_SECONDS", "soon", 1);
  EXPECT_EQ(reader_limits().wall_seconds, 60u);
  ::unsetenv("IBFVS_READER_SECONDS");
}

TEST(Isolation, AMeshRoundTripsAndAShortRecordIsRefused) {
  TriMesh m = make_sphere(1.0f, 8, 16);
  m.vectors.assign(m.vertex_count(), glm::vec3(1, 2, 3));
  m.scalars["p"].assign(m.vertex_count(), 4.0f);
  m.vector_arrays["U"].assign(m.vertex_count(), glm::vec3(5, 6, 7));
  m.other_arrays["T"] = 9;
  ByteWriter out;
  put_mesh(out, m);
  out.put(std::vector<std::string>{"a", "bc"});
  const std::string bytes = out.take();
  ByteReader in(bytes, "f");
  const TriMesh back = get_mesh(in);
  EXPECT_EQ(back.positions, m.positions);
  EXPECT_EQ(back.normals, m.normals);
  EXPECT_EQ(back.triangles, m.triangles);
  EXPECT_EQ(back.vectors, m.vectors);
  EXPECT_EQ(back.scalars, m.scalars);
  EXPECT_EQ(back.vector_arrays, m.vector_arrays);
  EXPECT_EQ(back.other_arrays, m.other_arrays);
  EXPECT_EQ(in.get_strings(), (std::vector<std::string>{"a", "bc"}));
  EXPECT_TRUE(in.done());
  ByteReader cut(std::string_view(bytes).substr(0, bytes.size() / 2), "f");
  EXPECT_THROW(get_mesh(cut), InputError);
}

}  // namespace
}  // namespace ibfvs
