#include <gtest/gtest.h>

#include "core/errors.hpp"

namespace navemu {

TEST(InputError, NamesFileLineAndField) {
  InputError e("data/x.05n", 12, "sqrtA", "not a number: 'abc'");
  EXPECT_STREQ(e.what(), "data/x.05n:12: sqrtA: not a number: 'abc'");
  EXPECT_EQ(e.line(), 12);
  EXPECT_EQ(e.field(), "sqrtA");
}

TEST(InputError, WithoutFile) {
  InputError e("--time", "expected ISO-8601 or WEEK:TOW");
  EXPECT_STREQ(e.what(), "--time: expected ISO-8601 or WEEK:TOW");
}

}  // namespace navemu
