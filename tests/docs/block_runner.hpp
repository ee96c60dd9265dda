#pragma once

// Runs a command block of a document as a reader would type it (docs/testing.md, "Docs that
// run"), and says what went wrong, naming the document's line, the command and its output.
//
// Every command runs in `bash` (the shell the docs are written for) in a process group of its own
// (setsid), so that what it starts in the background, and what those start, is stopped with it:
// SIGINT, as a reader's Ctrl-C, then SIGTERM, then SIGKILL. Use from one thread (the process
// becomes the subreaper of what the blocks leave, to reap it).

#include <chrono>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "tests/docs/doc_block.hpp"

namespace fleetmap::docs {

struct RunSettings {
  std::filesystem::path directory;  // where the commands run
  // Added to (or overriding) the test's own environment: PATH, FLEETMAP_DOMAIN...
  std::map<std::string, std::string> environment;
  std::chrono::milliseconds time_limit = std::chrono::seconds(60);  // per block
  std::chrono::milliseconds stop_limit = std::chrono::seconds(20);  // from SIGINT to exit
};

// A plain block (BlockMode::kRun): its lines run as one script with `set -e -o pipefail`, so it
// fails at the first command that fails. A command put in the background (`&`) is not waited for,
// and its exit code is not seen: it is stopped when the script ends. Returns the failures, each
// "FILE:LINE: what" followed by the output; empty when the block ran as written.
std::vector<std::string> RunBlock(const DocBlock& block, const RunSettings& settings);

// A long-running block (BlockMode::kLongRunning): each command is a program that runs until
// stopped, as in a terminal of its own (a trailing `&` changes nothing). All start at once, must
// still run, or have exited 0, after `block.hold_seconds`, and then each must exit 0 within
// `stop_limit` of a SIGINT.
std::vector<std::string> RunLongRunning(const DocBlock& block, const RunSettings& settings);

}  // namespace fleetmap::docs
