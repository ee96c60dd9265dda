#include "common/core/status.hpp"

#include <gtest/gtest.h>

namespace fleetmap {
namespace {

StatusOr<int> ParsePositive(int value) {
  if (value <= 0)
    return InvalidArgumentError("value " + std::to_string(value) + " is not positive");
  return value;
}

Status DoubleIt(int value, int* out) {
  FLEETMAP_ASSIGN_OR_RETURN(const int parsed, ParsePositive(value));
  *out = 2 * parsed;
  return Status::Ok();
}

TEST(StatusTest, OkByDefault) {
  const Status status;
  EXPECT_TRUE(status.ok());
  EXPECT_EQ(status.ToString(), "OK");
}

TEST(StatusTest, ErrorCarriesCodeAndMessage) {
  const Status status = NotFoundError("map.yaml: no such file");
  EXPECT_FALSE(status.ok());
  EXPECT_EQ(status.code(), StatusCode::kNotFound);
  EXPECT_EQ(status.ToString(), "NOT_FOUND: map.yaml: no such file");
}

TEST(StatusTest, WithContextPrefixesErrorsOnly) {
  EXPECT_EQ(DataLossError("truncated").WithContext("a.pgm").message(), "a.pgm: truncated");
  EXPECT_TRUE(Status::Ok().WithContext("a.pgm").ok());
}

TEST(StatusOrTest, HoldsValueOrError) {
  const StatusOr<int> good = ParsePositive(3);
  ASSERT_TRUE(good.ok());
  EXPECT_EQ(*good, 3);
  const StatusOr<int> bad = ParsePositive(-1);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().code(), StatusCode::kInvalidArgument);
}

TEST(StatusOrTest, AssignOrReturnPropagates) {
  int out = 0;
  EXPECT_TRUE(DoubleIt(4, &out).ok());
  EXPECT_EQ(out, 8);
  const Status error = DoubleIt(0, &out);
  EXPECT_EQ(error.message(), "value 0 is not positive");
  EXPECT_EQ(out, 8);
}

}  // namespace
}  // namespace fleetmap
