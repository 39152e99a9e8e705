#pragma once
// A GoogleTest fixture with one headless OpenGL 4.5 context per test suite and
// KHR_debug on: any GL error recorded during a test fails it.

#include <memory>

#include <gtest/gtest.h>

#include "ibfvs/gl/context.h"

namespace ibfvs::test {

class GlTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    gl::ContextOptions options;
    options.debug = true;
    context_ = std::make_unique<gl::HeadlessContext>(options);
  }
  static void TearDownTestSuite() { context_.reset(); }
  void TearDown() override { EXPECT_NO_THROW(context_->throw_if_errors()); }

  static gl::HeadlessContext& context() { return *context_; }

 private:
  static inline std::unique_ptr<gl::HeadlessContext> context_;
};

}  // namespace ibfvs::test
