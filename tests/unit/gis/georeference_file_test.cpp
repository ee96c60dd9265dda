// The georeference side file: beside the map YAML, read back by a YAML reader (yaml-cpp, not the
// writer's code) to the values given, whatever the map's file name holds.

#include "common/gis/georeference_file.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

namespace fleetmap::gis {
namespace {

using ::testing::HasSubstr;

TEST(GeoreferenceFileTest, SitsBesideTheMapYaml) {
  EXPECT_EQ(GeoreferenceFilePath("out/fused.yaml"), "out/fused.georef.yaml");
  EXPECT_EQ(GeoreferenceFilePath("/maps/house.yml"), "/maps/house.georef.yaml");
  EXPECT_EQ(GeoreferenceFilePath("house"), "house.georef.yaml");
}

TEST(GeoreferenceFileTest, ReadsBackAsTheOriginGiven) {
  StatusOr<Georeference> georeference =
      Georeference::Create({.latitude = 48.8583701, .longitude = -2.2944813, .yaw = -12.5});
  ASSERT_TRUE(georeference.ok()) << georeference.status();
  const std::string text = GeoreferenceFileText(*georeference, "fused: #1.yaml", "fleet");
  const YAML::Node yaml = YAML::Load(text);
  EXPECT_EQ(yaml["map"].as<std::string>(), "fused: #1.yaml");
  EXPECT_EQ(yaml["frame"].as<std::string>(), "fleet");
  EXPECT_EQ(yaml["crs"].as<std::string>(), "EPSG:4326");
  EXPECT_EQ(yaml["latitude"].as<double>(), 48.8583701);
  EXPECT_EQ(yaml["longitude"].as<double>(), -2.2944813);
  EXPECT_EQ(yaml["yaw"].as<double>(), -12.5);
  EXPECT_EQ(yaml["proj_pipeline"].as<std::string>(), georeference->ProjPipeline());
  // The digits given, not a float's expansion of them; the yaw's convention said.
  EXPECT_THAT(text, HasSubstr("latitude: 48.8583701\n"));
  EXPECT_THAT(text, HasSubstr("counter-clockwise from East"));
}

}  // namespace
}  // namespace fleetmap::gis
