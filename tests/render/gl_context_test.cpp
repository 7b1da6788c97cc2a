// SPDX-License-Identifier: MIT
#include "render/gl_context.h"

#include <gtest/gtest.h>

#include <cfenv>

#include "rope/common/error.h"

namespace rope::render {
namespace {

TEST(GlContext, CreatesACoreProfileContextOnLlvmpipe) {
  GlContext context(64, 32);
  EXPECT_EQ(context.width(), 64);
  EXPECT_EQ(context.height(), 32);
  EXPECT_NE(context.version().find("Core Profile"), std::string::npos) << context.version();
  EXPECT_FALSE(context.rendererName().empty());
  EXPECT_NO_THROW(context.makeCurrent());
}

TEST(GlContext, TwoContextsCanTakeTurns) {
  GlContext first(16, 16);
  GlContext second(32, 32);
  EXPECT_NO_THROW(first.makeCurrent());
  EXPECT_NO_THROW(second.makeCurrent());
}

TEST(GlContext, KeepsTheCallersFloatingPointTraps) {
  // The test main traps invalid/divide-by-zero/overflow; Mesa must run without them and the traps
  // must be back afterwards.
  const int before = fegetexcept();
  ASSERT_NE(before & FE_INVALID, 0);
  { GlContext context(32, 32); }
  EXPECT_EQ(fegetexcept(), before);
}

TEST(GlContext, RejectsBadSizes) {
  try {
    GlContext context(0, 10);
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(e.parameter(), "width");
  }
  EXPECT_THROW(GlContext(10, 20000), InvalidArgument);
}

}  // namespace
}  // namespace rope::render
