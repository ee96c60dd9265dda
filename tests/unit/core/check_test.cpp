#include "common/core/check.hpp"

#include <gtest/gtest.h>

namespace fleetmap {
namespace {

int Halve(int even) {
  FLEETMAP_CHECK(even % 2 == 0, "Halve needs an even number");
  return even / 2;
}

TEST(CheckDeathTest, PassesWhenTheConditionHolds) { EXPECT_EQ(Halve(8), 4); }

// The suite is built in Release (NDEBUG): these die only because the check is never compiled out.
TEST(CheckDeathTest, StopsTheProgramNamingTheConditionAndTheMessage) {
  EXPECT_DEATH(Halve(3), "check failed: even % 2 == 0: Halve needs an even number");
}

TEST(CheckDeathTest, NamesTheFileAndLineWithoutAMessage) {
  EXPECT_DEATH(FLEETMAP_CHECK(1 + 1 == 3), "check_test.cpp:[0-9]+: check failed: 1 \\+ 1 == 3");
}

}  // namespace
}  // namespace fleetmap
