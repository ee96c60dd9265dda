#include "tests/docs/doc_block.hpp"

#include <algorithm>
#include <cctype>
#include <optional>
#include <regex>
#include <set>
#include <sstream>

namespace fleetmap::docs {
namespace {

const std::set<std::string>& CommandLanguages() {
  static const std::set<std::string> languages = {"sh", "bash", "shell", "console"};
  return languages;
}

std::string Trim(const std::string& text) {
  const size_t first = text.find_first_not_of(" \t");
  if (first == std::string::npos) return "";
  const size_t last = text.find_last_not_of(" \t");
  return text.substr(first, last - first + 1);
}

bool EndsWithBackslash(const std::string& line) {
  const std::string trimmed = Trim(line);
  return !trimmed.empty() && trimmed.back() == '\\';
}

// A marker: `<!-- docs-test: MODE [SECONDS] [— reason] -->`.
struct Marker {
  int line = 0;
  BlockMode mode = BlockMode::kRun;
  double hold_seconds = 3.0;
  std::string reason;
  std::vector<std::string> errors;
};

std::optional<Marker> ParseMarker(const std::string& text, int line) {
  static const std::regex kMarker(R"(^\s*<!--\s*docs-test:\s*(.*?)\s*-->\s*$)");
  std::smatch match;
  if (!std::regex_match(text, match, kMarker)) return std::nullopt;
  Marker marker;
  marker.line = line;
  std::istringstream words(match[1].str());
  std::string mode;
  words >> mode;
  std::string rest;
  std::getline(words, rest);
  rest = Trim(rest);
  if (mode == "long-running" && !rest.empty() &&
      std::isdigit(static_cast<unsigned char>(rest[0]))) {
    size_t used = 0;
    marker.hold_seconds = std::stod(rest, &used);
    rest = Trim(rest.substr(used));
  }
  // The reason follows a dash (an em dash or a hyphen) or a colon.
  for (const std::string separator : {"\u2014", "--", "-", ":"}) {
    if (rest.rfind(separator, 0) == 0) {
      rest = Trim(rest.substr(separator.size()));
      break;
    }
  }
  marker.reason = rest;
  if (mode == "skip") {
    marker.mode = BlockMode::kSkip;
    if (marker.reason.empty()) marker.errors.push_back("a skip marker must say why");
  } else if (mode == "synopsis") {
    marker.mode = BlockMode::kSynopsis;
  } else if (mode == "long-running") {
    marker.mode = BlockMode::kLongRunning;
  } else {
    marker.errors.push_back("unknown docs-test marker '" + mode +
                            "' (skip, synopsis or long-running)");
  }
  return marker;
}

// A block that runs must not choose its DDS domain: the test gives each block its own through
// FLEETMAP_DOMAIN, so that parallel runs never meet (house rule 16).
std::optional<std::string> PinnedDomain(const DocBlock& block) {
  static const std::regex kPinned(R"((--domain[ =]+[0-9])|(FLEETMAP_DOMAIN=))");
  for (const std::string& line : TypedLines(block)) {
    if (std::regex_search(line, kPinned)) return line;
  }
  return std::nullopt;
}

// A block that runs must not build, install or change the machine (the tests run as root in CI,
// and a build in a test would take minutes): such a block is skipped, with its reason.
std::optional<std::string> MachineCommand(const DocBlock& block) {
  static const std::set<std::string> kCommands = {"sudo",    "su",        "apt",    "apt-get",
                                                  "dpkg",    "systemctl", "docker", "podman",
                                                  "buildah", "make",      "cmake",  "ctest"};
  static const std::regex kComment(R"((^|\s)#.*$)");
  static const std::regex kAssignment(R"(^[A-Za-z_][A-Za-z0-9_]*=.*$)");
  for (const std::string& line : TypedLines(block)) {
    const std::string code = std::regex_replace(line, kComment, "");
    if (code.find("install-deps.sh") != std::string::npos) return "install-deps.sh";
    // The first word of each command of the line (after `;`, `&&`, `|`, `(`...), past VAR=value.
    std::string commands = code;
    for (char& c : commands) {
      if (c == ';' || c == '&' || c == '|' || c == '(' || c == ')' || c == '`') c = '\n';
    }
    std::istringstream split(commands);
    for (std::string command; std::getline(split, command);) {
      std::istringstream words(command);
      std::string word;
      while (words >> word && std::regex_match(word, kAssignment)) {
      }
      if (kCommands.count(word) > 0) return word;
    }
  }
  return std::nullopt;
}

}  // namespace

bool DocBlock::IsCommands() const { return CommandLanguages().count(language) > 0; }

std::string DocBlock::Where() const { return file + ":" + std::to_string(line); }

std::vector<DocBlock> ReadDocBlocks(const std::string& file, const std::string& text) {
  static const std::regex kOpening(R"(^(\s*)```+\s*([^`\s]*).*$)");
  static const std::regex kClosing(R"(^\s*```+\s*$)");
  std::vector<std::string> lines;
  {
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
  }
  std::vector<DocBlock> blocks;
  std::optional<Marker> pending;  // a marker waiting for its fence
  auto orphan = [&](const Marker& marker, const std::string& why) {
    DocBlock error;
    error.file = file;
    error.line = marker.line;
    error.errors.push_back(why);
    blocks.push_back(error);
  };
  for (size_t i = 0; i < lines.size(); ++i) {
    const int line_number = static_cast<int>(i) + 1;
    if (std::optional<Marker> marker = ParseMarker(lines[i], line_number)) {
      if (pending) orphan(*pending, "a docs-test marker not followed by a block");
      pending = marker;
      continue;
    }
    std::smatch opening;
    if (!std::regex_match(lines[i], opening, kOpening)) {
      if (pending && !Trim(lines[i]).empty()) {
        orphan(*pending, "a docs-test marker not followed by a block");
        pending.reset();
      }
      continue;
    }
    DocBlock block;
    block.file = file;
    block.line = line_number;
    block.language = opening[2].str();
    const size_t indent = opening[1].length();
    bool closed = false;
    for (++i; i < lines.size(); ++i) {
      if (std::regex_match(lines[i], kClosing)) {
        closed = true;
        break;
      }
      // A block inside a list item is indented as its fence is; the reader types it without.
      const size_t spaces = std::min(lines[i].find_first_not_of(' '), lines[i].size());
      block.lines.push_back(lines[i].substr(std::min(indent, spaces)));
    }
    if (!closed) block.errors.push_back("the block has no closing fence");
    if (block.language.empty()) {
      block.errors.push_back(
          "a block without a language: ```sh (or console) for commands, ```text for output, "
          "pictures and other text that is not typed");
    }
    if (pending) {
      if (!block.IsCommands()) {
        block.errors.push_back("a docs-test marker on a block that is not commands (```" +
                               block.language + ")");
      }
      block.mode = pending->mode;
      block.hold_seconds = pending->hold_seconds;
      block.reason = pending->reason;
      block.errors.insert(block.errors.end(), pending->errors.begin(), pending->errors.end());
      pending.reset();
    }
    if (block.IsCommands() &&
        (block.mode == BlockMode::kRun || block.mode == BlockMode::kLongRunning)) {
      if (std::optional<std::string> pinned = PinnedDomain(block)) {
        block.errors.push_back("sets its own DDS domain (" + Trim(*pinned) +
                               "): a block that runs takes FLEETMAP_DOMAIN from the test");
      }
      if (std::optional<std::string> command = MachineCommand(block)) {
        block.errors.push_back("runs `" + *command +
                               "`, which builds, installs or changes the machine: not in a "
                               "test (mark the block <!-- docs-test: skip \u2014 why -->)");
      }
    }
    blocks.push_back(block);
  }
  if (pending) orphan(*pending, "a docs-test marker not followed by a block");
  return blocks;
}

std::vector<std::string> TypedLines(const DocBlock& block) {
  if (block.language != "console") return block.lines;
  std::vector<std::string> typed;
  bool continued = false;  // the previous typed line ended with a backslash
  for (const std::string& line : block.lines) {
    if (continued) {
      typed.push_back(line);
    } else if (line == "$" || line.rfind("$ ", 0) == 0) {
      typed.push_back(line.size() > 2 ? line.substr(2) : "");
    } else {
      typed.push_back("");  // output
      continued = false;
      continue;
    }
    continued = EndsWithBackslash(typed.back());
  }
  return typed;
}

std::vector<TypedCommand> TypedCommands(const DocBlock& block) {
  const std::vector<std::string> typed = TypedLines(block);
  std::vector<TypedCommand> commands;
  bool continued = false;
  for (size_t i = 0; i < typed.size(); ++i) {
    const std::string trimmed = Trim(typed[i]);
    if (continued) {
      commands.back().text += "\n" + typed[i];
    } else if (!trimmed.empty() && trimmed[0] != '#') {
      commands.push_back({block.LineOf(i), typed[i]});
    } else {
      continue;
    }
    continued = EndsWithBackslash(typed[i]);
  }
  return commands;
}

}  // namespace fleetmap::docs
