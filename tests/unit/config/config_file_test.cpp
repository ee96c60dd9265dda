#include "common/config/config_file.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

#include "tests/scratch_dir.hpp"

namespace fleetmap::config {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::IsEmpty;

class ConfigFileTest : public ::testing::Test {
 protected:
  std::string Write(const std::string& text) {
    const std::string path = scratch_.Path("settings.yaml");
    std::ofstream(path) << text;
    return path;
  }

  // key=value1,value2 for each setting, in the file's order.
  std::vector<std::string> Read(const std::string& text,
                                const std::string& node = "fleetmap_server") {
    const auto settings = ReadConfigFile(Write(text), node);
    EXPECT_TRUE(settings.ok()) << settings.status().message();
    std::vector<std::string> listed;
    if (!settings.ok()) return listed;
    for (const ConfigSetting& setting : *settings) {
      std::string line = setting.key + "=";
      for (size_t i = 0; i < setting.values.size(); ++i) {
        line += (i > 0 ? "," : "") + setting.values[i];
      }
      listed.push_back(line);
    }
    return listed;
  }

  std::string Error(const std::string& text, const std::string& node = "fleetmap_server") {
    const auto settings = ReadConfigFile(Write(text), node);
    EXPECT_FALSE(settings.ok());
    return settings.ok() ? std::string() : settings.status().message();
  }

  testing::ScratchDir scratch_{"config_file"};
};

TEST_F(ConfigFileTest, KeysAreTheLongOptionsWithUnderscoresAndDotsAsDashes) {
  EXPECT_THAT(
      Read("store: a.db\ntile_size: 5\nplacement.confidence: 0.9\nno-quarantine: true\n"),
      ElementsAre("store=a.db", "tile-size=5", "placement-confidence=0.9", "no-quarantine=true"));
}

TEST_F(ConfigFileTest, NestedMapsJoinTheirKeysAndSequencesGiveSeveralValues) {
  EXPECT_THAT(Read("placement:\n  confidence: 0.9\n  max_drift: 0.03\n"
                   "fleet-from-map: [2.0, -1.5, 90]\n"),
              ElementsAre("placement-confidence=0.9", "placement-max-drift=0.03",
                          "fleet-from-map=2.0,-1.5,90"));
}

TEST_F(ConfigFileTest, NullLeavesTheOptionOutAndAnEmptyFileHasNoSettings) {
  EXPECT_THAT(Read("store: ~\ntile-size: 5\n"), ElementsAre("tile-size=5"));
  EXPECT_THAT(Read(""), IsEmpty());
  EXPECT_THAT(Read("# only a comment\n"), IsEmpty());
}

TEST_F(ConfigFileTest, EachSettingKnowsItsLine) {
  const auto settings =
      ReadConfigFile(Write("# header\n\nstore: a.db\nplacement:\n  x: 1\n"), "fleetmap_server");
  ASSERT_TRUE(settings.ok()) << settings.status().message();
  ASSERT_EQ(settings->size(), 2u);
  EXPECT_THAT((*settings)[0].location, ::testing::EndsWith("settings.yaml:3"));
  EXPECT_THAT((*settings)[1].location, ::testing::EndsWith("settings.yaml:5"));
  EXPECT_FALSE((*settings)[0].for_every_node);
}

TEST_F(ConfigFileTest, RosParamsFileGivesItsOwnNodeOverTheWildcardAndSkipsOtherNodes) {
  const std::string params =
      "/**:\n"
      "  ros__parameters:\n"
      "    use_sim_time: false\n"
      "    tile_size: 7\n"
      "amcl:\n"
      "  ros__parameters:\n"
      "    alpha1: 0.2\n"
      "/robot1/fleetmap_server:\n"
      "  ros__parameters:\n"
      "    tile_size: 4\n"
      "    store: /var/lib/fleetmap/fleet.db\n";
  const auto settings = ReadConfigFile(Write(params), "fleetmap_server");
  ASSERT_TRUE(settings.ok()) << settings.status().message();
  std::vector<std::string> listed;
  for (const ConfigSetting& setting : *settings) {
    listed.push_back(setting.key + "=" + setting.values.at(0) +
                     (setting.for_every_node ? " (every node)" : ""));
  }
  // The wildcard first, so that the node's own tile_size comes later and wins.
  EXPECT_THAT(listed, ElementsAre("use-sim-time=false (every node)", "tile-size=7 (every node)",
                                  "tile-size=4", "store=/var/lib/fleetmap/fleet.db"));
}

TEST_F(ConfigFileTest, RosParamsFileMatchesPlainSlashedAndNamespacedNodeNames) {
  for (const std::string node :
       {"fleetmap_view", "/fleetmap_view", "/site/fleetmap_view", "/**/fleetmap_view"}) {
    EXPECT_THAT(Read(node + ":\n  ros__parameters:\n    port: 9000\n", "fleetmap_view"),
                ElementsAre("port=9000"))
        << node;
  }
  // A name that only ends like the node's is another node.
  EXPECT_THAT(Read("my_fleetmap_view:\n  ros__parameters:\n    port: 9000\n", "fleetmap_view"),
              IsEmpty());
}

TEST_F(ConfigFileTest, RosParamsFileWithoutThisNodeGivesNothingAndANoteListingItsNodes) {
  std::string note;
  const auto settings = ReadConfigFile(
      Write("amcl:\n  ros__parameters: {alpha1: 0.2}\nbt_navigator:\n  ros__parameters: {}\n"),
      "fleetmap_server", &note);
  ASSERT_TRUE(settings.ok()) << settings.status().message();
  EXPECT_THAT(*settings, IsEmpty());
  EXPECT_THAT(note, HasSubstr("no section for fleetmap_server"));
  EXPECT_THAT(note, HasSubstr("amcl, bt_navigator"));
}

TEST_F(ConfigFileTest, APlainKeyBesideNodeSectionsIsRefusedWithItsLine) {
  EXPECT_THAT(Error("fleetmap_server:\n  ros__parameters: {store: a.db}\ntile_size: 5\n"),
              HasSubstr("settings.yaml:3: tile_size is not a node's section"));
}

TEST_F(ConfigFileTest, BadFilesNameTheFileAndLine) {
  EXPECT_THAT(Error("store: a.db\ntile-size: [1\n"), HasSubstr("settings.yaml:3:1: not YAML"));
  EXPECT_THAT(Error("- store\n- a.db\n"), HasSubstr("is a map of option names to values"));
  EXPECT_THAT(Error("store: a.db\ntile_size: 4\ntile-size: 5\n"),
              HasSubstr("settings.yaml:3: tile-size is set twice (first at "));
  EXPECT_THAT(Error("fleet-from-map: [[1, 2], 3]\n"),
              HasSubstr("settings.yaml:1: fleet-from-map takes a list of plain values"));
  const auto missing = ReadConfigFile(scratch_.Path("missing.yaml"), "fleetmap_server");
  ASSERT_FALSE(missing.ok());
  EXPECT_THAT(missing.status().message(), HasSubstr("missing.yaml: cannot be read"));
}

}  // namespace
}  // namespace fleetmap::config
