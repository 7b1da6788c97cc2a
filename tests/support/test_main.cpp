// SPDX-License-Identifier: MIT
// GoogleTest main for every SplineRope test binary: floating-point exceptions are trapped, so a NaN
// or an overflow in SplineRope code fails the test where it happens.
#include <gtest/gtest.h>

#include "support/fp_exceptions.h"

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  rope::test::enableFloatingPointTraps();
  return RUN_ALL_TESTS();
}
