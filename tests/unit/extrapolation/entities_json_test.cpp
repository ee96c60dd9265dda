#include "common/extrapolation/entities_json.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace fleetmap::extrapolation {
namespace {

using ::testing::HasSubstr;

std::string Wrap(const std::string& entities) {
  return R"({"frame": "map", "entities": [)" + entities + "]}";
}

const char* kDoor =
    R"({"class": "door", "id": "d1", "hinge": [1, 2], "latch": [2, 2], "opening_direction": [0, 1]})";
const char* kStairs =
    R"({"class": "stairs", "id": "s1", "position": [5, 5], "ascending": [2, 0], "step_width": 1.2,
        "next_floor_height": 3.0})";
const char* kPerson =
    R"({"class": "person", "id": "p1", "left_view": true, "track": [
        {"stamp": 0.0, "position": [0, 0], "heading": 0},
        {"stamp": 0.5, "position": [0.5, 0], "heading": 0}]})";

TEST(EntitiesJsonTest, ParsesEachClass) {
  const auto parsed =
      ParseEntitiesJson(Wrap(std::string(kDoor) + "," + kStairs + "," + kPerson), "e.json");
  ASSERT_TRUE(parsed.ok()) << parsed.status();
  EXPECT_TRUE(parsed->warnings.empty());
  ASSERT_EQ(parsed->entities.doors.size(), 1u);
  EXPECT_EQ(parsed->entities.doors[0].id, "d1");
  EXPECT_EQ(parsed->entities.doors[0].hinge, Point2(1, 2));
  EXPECT_FALSE(parsed->entities.doors[0].open);
  ASSERT_EQ(parsed->entities.stairs.size(), 1u);
  EXPECT_EQ(parsed->entities.stairs[0].ascending, Vector2(1, 0));  // normalised
  EXPECT_DOUBLE_EQ(parsed->entities.stairs[0].step_width, 1.2);
  ASSERT_EQ(parsed->entities.people.size(), 1u);
  EXPECT_TRUE(parsed->entities.people[0].left_view);
  EXPECT_EQ(parsed->entities.people[0].points.size(), 2u);
}

TEST(EntitiesJsonTest, RoundTrips) {
  const auto parsed =
      ParseEntitiesJson(Wrap(std::string(kDoor) + "," + kStairs + "," + kPerson), "e.json");
  ASSERT_TRUE(parsed.ok());
  const auto again = ParseEntitiesJson(EntitiesToJson(parsed->entities), "again");
  ASSERT_TRUE(again.ok()) << again.status();
  EXPECT_EQ(EntitiesToJson(again->entities), EntitiesToJson(parsed->entities));
}

TEST(EntitiesJsonTest, BadFilesAreErrorsNamingTheSource) {
  for (const char* text : {"not json", "[1, 2]", "{}", R"({"entities": 3})"}) {
    const auto parsed = ParseEntitiesJson(text, "bad.json");
    ASSERT_FALSE(parsed.ok()) << text;
    EXPECT_EQ(parsed.status().code(), StatusCode::kInvalidArgument);
    EXPECT_THAT(parsed.status().message(), HasSubstr("bad.json")) << text;
  }
}

// Each unusable entry is skipped with a warning naming it; the good door is still used.
void ExpectSkipped(const std::string& entry, const std::string& why) {
  const auto parsed = ParseEntitiesJson(Wrap(std::string(kDoor) + "," + entry), "e.json");
  ASSERT_TRUE(parsed.ok()) << parsed.status();
  EXPECT_EQ(parsed->entities.doors.size() + parsed->entities.stairs.size() +
                parsed->entities.people.size(),
            1u)
      << entry;
  ASSERT_FALSE(parsed->warnings.empty()) << entry;
  EXPECT_THAT(parsed->warnings.back(), HasSubstr("x9")) << entry;
  EXPECT_THAT(parsed->warnings.back(), HasSubstr(why)) << entry;
}

TEST(EntitiesJsonTest, UnknownClassIsSkipped) {
  ExpectSkipped(R"({"class": "elevator", "id": "x9"})", "unknown class 'elevator'");
}

TEST(EntitiesJsonTest, MissingFieldIsSkipped) {
  ExpectSkipped(R"({"class": "door", "id": "x9", "hinge": [0, 0]})", "missing 'latch'");
  ExpectSkipped(R"({"class": "stairs", "id": "x9", "position": [0, 0], "ascending": [1, 0]})",
                "missing 'step_width'");
  ExpectSkipped(R"({"class": "person", "id": "x9"})", "missing 'track'");
}

TEST(EntitiesJsonTest, NonFiniteNumbers) {
  // JSON has no NaN: a bare NaN or an overflowing number makes the file unreadable (an error
  // naming it); a "NaN" string is a mistyped field (the entry is skipped).
  for (const char* number : {"NaN", "1e999"}) {
    const auto parsed =
        ParseEntitiesJson(Wrap(std::string(R"({"class": "door", "id": "x9", "hinge": [)") + number +
                               R"(, 0], "latch": [1, 0]})"),
                          "nan.json");
    ASSERT_FALSE(parsed.ok()) << number;
    EXPECT_THAT(parsed.status().message(), HasSubstr("nan.json"));
  }
  ExpectSkipped(R"({"class": "stairs", "id": "x9", "position": [0, 0], "ascending": [1, 0],
                    "step_width": "NaN"})",
                "'step_width' is not a number");
}

TEST(EntitiesJsonTest, ZeroWidthDoorIsSkipped) {
  ExpectSkipped(R"({"class": "door", "id": "x9", "hinge": [3, 3], "latch": [3, 3]})", "width 0");
}

TEST(EntitiesJsonTest, OnePointTrackIsSkipped) {
  ExpectSkipped(R"({"class": "person", "id": "x9", "track": [
                    {"stamp": 0, "position": [0, 0], "heading": 0}]})",
                "at least two usable points");
}

TEST(EntitiesJsonTest, MissingIdAndDuplicatesAreSkipped) {
  const auto parsed = ParseEntitiesJson(
      Wrap(std::string(kDoor) + "," + kDoor + R"(, {"class": "door", "hinge": [0, 0]})"), "e.json");
  ASSERT_TRUE(parsed.ok());
  EXPECT_EQ(parsed->entities.doors.size(), 1u);
  ASSERT_EQ(parsed->warnings.size(), 2u);
  EXPECT_THAT(parsed->warnings[0], HasSubstr("duplicate id"));
  EXPECT_THAT(parsed->warnings[1], HasSubstr("missing 'id'"));
}

TEST(EntitiesJsonTest, MissingOpeningDirectionIsLeftToTheMap) {
  const auto parsed = ParseEntitiesJson(
      Wrap(R"({"class": "door", "id": "d", "hinge": [0, 0], "latch": [1, 0]})"), "e.json");
  ASSERT_TRUE(parsed.ok());
  ASSERT_EQ(parsed->entities.doors.size(), 1u);
  EXPECT_EQ(parsed->entities.doors[0].opening_direction, Vector2::Zero());
}

}  // namespace
}  // namespace fleetmap::extrapolation
