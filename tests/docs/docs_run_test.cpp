// Issue 33, "Docs that run": every command block of README.md and docs/*.md runs as written, so
// a document that drifts from the code fails here (docs/testing.md, "Docs that run"). One case
// per document: its blocks run in order in one scratch directory, as a reader follows them, each
// on a DDS domain of its own.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "common/process/subprocess.hpp"
#include "tests/docs/block_runner.hpp"
#include "tests/docs/doc_block.hpp"
#include "tests/docs/synopsis_check.hpp"
#include "tests/scratch_dir.hpp"

namespace fleetmap::docs {
namespace {

namespace fs = std::filesystem;

const fs::path kSource = FLEETMAP_SOURCE_DIR;
const fs::path kBuild = FLEETMAP_BINARY_DIR;

// The documents, relative to the source tree: README.md and docs/*.md, as the tree holds them
// (tests/docs/CMakeLists.txt relinks the binary when a page is added, so ctest lists it).
std::vector<std::string> Documents() {
  std::vector<std::string> documents = {"README.md"};
  for (const auto& entry : fs::directory_iterator(kSource / "docs")) {
    if (entry.path().extension() == ".md") {
      documents.push_back("docs/" + entry.path().filename().string());
    }
  }
  std::sort(documents.begin() + 1, documents.end());
  return documents;
}

std::string CaseName(const ::testing::TestParamInfo<std::string>& info) {
  std::string name = info.param;
  std::replace_if(
      name.begin(), name.end(), [](char c) { return !std::isalnum(static_cast<unsigned char>(c)); },
      '_');
  return name;
}

// The programs as the docs name them, from this build tree: first on the blocks' PATH, and what
// a synopsis is checked against.
const std::map<std::string, std::string>& Programs() {
  static const std::map<std::string, std::string> programs = {
      {"fleetmap", (kBuild / "cli/fleetmap").string()},
      {"fleetmap-server", (kBuild / "server/fleetmap-server").string()},
      {"fleetmap-agent", (kBuild / "robot_agent/fleetmap-agent").string()},
  };
  return programs;
}

// Where the docs call programs by their path in the build tree (build/tests/hostile_peer/...).
const std::vector<std::string>& BuiltPrograms() {
  static const std::vector<std::string> programs = {"cli/fleetmap", "server/fleetmap-server",
                                                    "robot_agent/fleetmap-agent",
                                                    "tests/hostile_peer/fleetmap-hostile-peer"};
  return programs;
}

// Lays the scratch directory out as the reader's checkout, where the docs' commands are typed:
// every top-level entry of the source tree is linked (tests/data, scripts, docker...), and
// `build/` holds links to this build's programs only, never to the build tree itself, which a
// block that configures or builds (a mistake the markers are for) would otherwise overwrite.
// What the blocks write stays in the scratch directory; build trees and outputs of the source
// tree (.gitignore: /build*/, /out/) are not linked.
void LayOutCheckout(const fs::path& scratch) {
  for (const auto& entry : fs::directory_iterator(kSource)) {
    const std::string name = entry.path().filename().string();
    if (name[0] == '.' || name.rfind("build", 0) == 0 || name == "out") continue;
    fs::create_symlink(entry.path(), scratch / name);
  }
  for (const std::string& program : BuiltPrograms()) {
    const fs::path link = scratch / "build" / program;
    fs::create_directories(link.parent_path());
    fs::create_symlink(kBuild / program, link);
  }
}

RunSettings SettingsFor(const fs::path& scratch) {
  RunSettings settings;
  settings.directory = scratch;
  std::string path;
  for (const auto& [name, program] : Programs()) {
    path += fs::path(program).parent_path().string() + ":";
  }
  const char* inherited = std::getenv("PATH");
  settings.environment["PATH"] = path + (inherited != nullptr ? inherited : "/usr/bin:/bin");
  // A domain of its own (claimed until this test ends) on loopback: blocks of parallel tests,
  // and other runs on this machine, never meet.
  settings.environment["FLEETMAP_DOMAIN"] = std::to_string(process::RandomDomainId());
  settings.environment["FLEETMAP_LOCALHOST_ONLY"] = "1";
  return settings;
}

class DocsRunTest : public ::testing::TestWithParam<std::string> {};

TEST_P(DocsRunTest, EveryCommandBlockRunsAsWritten) {
  const std::string document = GetParam();
  const std::string text = testing::ReadFile((kSource / document).string());
  ASSERT_FALSE(text.empty()) << document << " cannot be read";
  const testing::ScratchDir scratch("docs");
  const fs::path directory = scratch.Path("");
  LayOutCheckout(directory);

  int ran = 0, long_running = 0, synopses = 0, skipped = 0;
  std::string skip_reasons;
  for (const DocBlock& block : ReadDocBlocks(document, text)) {
    for (const std::string& error : block.errors) ADD_FAILURE() << block.Where() << ": " << error;
    if (!block.errors.empty() || !block.IsCommands()) continue;
    std::vector<std::string> failures;
    switch (block.mode) {
      case BlockMode::kRun:
        ++ran;
        failures = RunBlock(block, SettingsFor(directory));
        break;
      case BlockMode::kLongRunning:
        ++long_running;
        failures = RunLongRunning(block, SettingsFor(directory));
        break;
      case BlockMode::kSynopsis:
        ++synopses;
        failures = CheckSynopsis(block, Programs());
        break;
      case BlockMode::kSkip:
        ++skipped;
        skip_reasons += "  " + block.Where() + ": " + block.reason + "\n";
        break;
    }
    for (const std::string& failure : failures) ADD_FAILURE() << failure;
  }
  std::cout << document << ": " << ran << " block(s) run, " << long_running << " long-running, "
            << synopses << " synopsis(es) checked, " << skipped << " skipped\n"
            << skip_reasons;
}

INSTANTIATE_TEST_SUITE_P(Docs, DocsRunTest, ::testing::ValuesIn(Documents()), CaseName);

}  // namespace
}  // namespace fleetmap::docs
