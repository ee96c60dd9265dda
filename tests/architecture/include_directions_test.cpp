#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "tests/architecture/include_rules.hpp"
#include "tests/scratch_dir.hpp"

namespace fleetmap::architecture {
namespace {

namespace fs = std::filesystem;

std::string Describe(const std::vector<IncludeViolation>& violations) {
  std::string text;
  for (const IncludeViolation& v : violations) {
    text +=
        v.file + ":" + std::to_string(v.line) + ": #include \"" + v.include + "\": " + v.why + "\n";
  }
  return text;
}

void WriteFile(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << text;
}

// The repository keeps the directions its own architecture document draws.
TEST(IncludeDirectionsTest, TheTreeKeepsTheDirectionsOfDocsArchitecture) {
  const fs::path root = FLEETMAP_SOURCE_DIR;
  StatusOr<IncludeRules> rules = ReadIncludeRules(root / "docs/architecture.md");
  ASSERT_TRUE(rules.ok()) << rules.status();
  EXPECT_GE(rules->may_include.size(), 10U);
  const std::vector<IncludeViolation> violations = CheckIncludes(root, *rules);
  EXPECT_TRUE(violations.empty()) << Describe(violations);
}

// The checker itself: on a small tree with one include of each forbidden kind, it names each.
class IncludeCheckerTest : public ::testing::Test {
 protected:
  IncludeCheckerTest() : dir_("include_rules"), root_(dir_.Path("repo")) {
    WriteFile(root_ / "docs/architecture.md", R"(# Parts
```include-rules
common/core ->
common/grid -> common/core   # grids know ids and poses
common/transport -> common/core common/grid idl
server -> common/core common/grid common/transport
edge-exception tests/wire/
```
)");
    WriteFile(root_ / "common/core/ids.hpp", "#pragma once\n#include <string>\n");
    WriteFile(root_ / "common/transport/internal/qos.hpp", "#include \"nav_msgs/msg/X.h\"\n");
    WriteFile(root_ / "common/transport/writer.hpp",
              "#include \"common/transport/internal/qos.hpp\"\n#include \"CLI/CLI.hpp\"\n");
    WriteFile(root_ / "server/node.cpp", "#include \"common/transport/writer.hpp\"\n");
    WriteFile(root_ / "tests/wire/peer.cpp", "#include \"common/transport/internal/qos.hpp\"\n");
  }

  std::vector<IncludeViolation> Check() {
    StatusOr<IncludeRules> rules = ReadIncludeRules(root_ / "docs/architecture.md");
    EXPECT_TRUE(rules.ok()) << rules.status();
    return rules.ok() ? CheckIncludes(root_, *rules) : std::vector<IncludeViolation>{};
  }

  testing::ScratchDir dir_;
  fs::path root_;
};

TEST_F(IncludeCheckerTest, AcceptsATreeThatKeepsTheRules) {
  EXPECT_TRUE(Check().empty()) << Describe(Check());
}

TEST_F(IncludeCheckerTest, NamesAnUpwardInclude) {
  WriteFile(root_ / "common/grid/grid.hpp", "\n#include \"common/transport/writer.hpp\"\n");
  const std::vector<IncludeViolation> violations = Check();
  ASSERT_EQ(violations.size(), 1U) << Describe(violations);
  EXPECT_EQ(violations[0].file, "common/grid/grid.hpp");
  EXPECT_EQ(violations[0].line, 2);
  EXPECT_EQ(violations[0].include, "common/transport/writer.hpp");
  EXPECT_NE(violations[0].why.find("common/grid may not include common/transport"),
            std::string::npos);
}

TEST_F(IncludeCheckerTest, NamesAnotherModulesInternalHeaderAndGeneratedTypes) {
  WriteFile(root_ / "server/peek.cpp", "#include \"common/transport/internal/qos.hpp\"\n");
  WriteFile(root_ / "tests/unit/msg_test.cpp", "#include \"nav_msgs/msg/X.h\"\n");
  const std::vector<IncludeViolation> violations = Check();
  ASSERT_EQ(violations.size(), 2U) << Describe(violations);
  EXPECT_NE(Describe(violations).find("server/peek.cpp:1"), std::string::npos);
  EXPECT_NE(Describe(violations).find("internal/ headers are private to common/transport"),
            std::string::npos);
  EXPECT_NE(Describe(violations).find("tests/unit/msg_test.cpp:1"), std::string::npos);
  EXPECT_NE(Describe(violations).find("generated DDS types stay in common/transport"),
            std::string::npos);
}

TEST_F(IncludeCheckerTest, NamesAModuleTheRulesDoNotKnow) {
  WriteFile(root_ / "common/shiny/new.hpp", "#pragma once\n");
  const std::vector<IncludeViolation> violations = Check();
  ASSERT_EQ(violations.size(), 1U) << Describe(violations);
  EXPECT_EQ(violations[0].why, "module common/shiny is not in the rules");
}

TEST_F(IncludeCheckerTest, RefusesARulesLineItCannotRead) {
  WriteFile(root_ / "docs/architecture.md", "```include-rules\ncommon/core => common/grid\n```\n");
  StatusOr<IncludeRules> rules = ReadIncludeRules(root_ / "docs/architecture.md");
  ASSERT_FALSE(rules.ok());
  EXPECT_NE(rules.status().message().find("architecture.md:2"), std::string::npos);
}

}  // namespace
}  // namespace fleetmap::architecture
