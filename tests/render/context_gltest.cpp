#include <vector>

#include <gtest/gtest.h>

#include "gl_fixture.h"
#include "ibfvs/core/support/error.h"
#include "ibfvs/gl/objects.h"

namespace ibfvs {
namespace {

class ContextGLTest : public test::GlTest {};

TEST_F(ContextGLTest, NamesTheRendererAndPlatform) {
  EXPECT_NE(context().renderer().find("OpenGL 4."), std::string::npos) << context().renderer();
  EXPECT_TRUE(context().platform() == "device" || context().platform() == "surfaceless");
  std::printf("renderer: %s (EGL %s)\n", context().renderer().c_str(),
              context().platform().c_str());
}

TEST_F(ContextGLTest, GlErrorsBecomeExceptions) {
  gl::Texture2D tex(4, 4, gl::Format::RGBA8);
  std::vector<float> small(4);
  // Reading 16 RGBA pixels into a 4-float buffer is refused by our wrapper...
  EXPECT_THROW(tex.read_float(small, 4), GraphicsError);
  // ...and a real GL error (an incomplete framebuffer read) is reported.
  gl::Framebuffer fb = gl::Framebuffer::create();
  std::vector<std::uint8_t> out(16 * 4);
  fb.read_rgba8(0, 4, 4, out);
  EXPECT_THROW(context().throw_if_errors(), GraphicsError);
}

TEST_F(ContextGLTest, ShaderErrorsCarryTheLog) {
  try {
    gl::Program p("#version 450 core\nvoid main() { gl_Position = vec4(0); }\n",
                  "#version 450 core\nout vec4 c; void main() { c = undefined_thing; }\n");
    FAIL();
  } catch (const GraphicsError& e) {
    EXPECT_NE(std::string(e.what()).find("fragment shader does not compile"), std::string::npos);
  }
}

TEST_F(ContextGLTest, RaiiObjectsMoveAndRelease) {
  gl::Texture2D a(2, 2, gl::Format::RGBA16F);
  const unsigned id = a.id();
  ASSERT_NE(id, 0u);
  gl::Texture2D b = std::move(a);
  EXPECT_EQ(b.id(), id);
  EXPECT_FALSE(static_cast<bool>(a));  // NOLINT(bugprone-use-after-move): the point of the test
}

}  // namespace
}  // namespace ibfvs
