#include "view/request_path.hpp"

#include <gtest/gtest.h>

#include <string>

namespace fleetmap::view {
namespace {

TEST(RequestPathTest, NamesTheRoutes) {
  EXPECT_EQ(RoutePath("/events"), PathRoute::kEvents);
  EXPECT_EQ(RoutePath("/map.png"), PathRoute::kMapImage);
  EXPECT_EQ(RoutePath("/"), PathRoute::kStaticFile);
  EXPECT_EQ(RoutePath("/view.js"), PathRoute::kStaticFile);
  EXPECT_EQ(RoutePath("/leaflet/images/marker-icon.png"), PathRoute::kStaticFile);
}

TEST(RequestPathTest, RefusesWhatCouldLeaveTheStaticFolder) {
  EXPECT_EQ(RoutePath(""), PathRoute::kNotFound);
  EXPECT_EQ(RoutePath("index.html"), PathRoute::kNotFound);
  EXPECT_EQ(RoutePath("/../secret"), PathRoute::kNotFound);
  EXPECT_EQ(RoutePath("/leaflet/../../secret"), PathRoute::kNotFound);
  EXPECT_EQ(RoutePath("/..\\secret"), PathRoute::kNotFound);
  EXPECT_EQ(RoutePath("/a\\b"), PathRoute::kNotFound);
}

TEST(RequestPathTest, RefusesControlCharacters) {
  EXPECT_EQ(RoutePath(std::string("/index.html\0.png", 16)), PathRoute::kNotFound);
  EXPECT_EQ(RoutePath("/index.html\n"), PathRoute::kNotFound);
  EXPECT_EQ(RoutePath("/index\x7f.html"), PathRoute::kNotFound);
  EXPECT_EQ(RoutePath("/caf\xc3\xa9.html"), PathRoute::kStaticFile);  // UTF-8 is a name
}

}  // namespace
}  // namespace fleetmap::view
