#include "tests/docs/synopsis_check.hpp"

#include <algorithm>
#include <filesystem>
#include <regex>
#include <sstream>

#include "common/process/subprocess.hpp"

namespace fleetmap::docs {
namespace {

struct Entry {
  int line = 0;
  std::vector<std::string> words;
};

std::vector<std::string> Words(const std::string& text) {
  std::vector<std::string> words;
  std::istringstream in(text);
  for (std::string word; in >> word;) words.push_back(word);
  return words;
}

std::vector<std::string> Split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream in(text);
  while (std::getline(in, part, separator)) parts.push_back(part);
  if (!text.empty() && text.back() == separator) parts.push_back("");
  return parts;
}

bool Contains(const std::vector<std::string>& list, const std::string& item) {
  return std::find(list.begin(), list.end(), item) != list.end();
}

// The block's entries: a line and the lines indented under it or joined by a backslash, split
// at `;`; comments removed; `a | b` written `a|b`.
std::vector<Entry> Entries(const DocBlock& block) {
  static const std::regex kComment(R"((^|\s)#.*$)");
  const std::vector<std::string> typed = TypedLines(block);  // a console block's output: ""
  std::vector<Entry> entries;
  bool continued = false;
  for (size_t i = 0; i < typed.size(); ++i) {
    std::string text = std::regex_replace(typed[i], kComment, "");
    const bool indented = !text.empty() && (text[0] == ' ' || text[0] == '\t');
    const size_t end = text.find_last_not_of(" \t");
    if (end == std::string::npos) {
      continued = false;
      continue;
    }
    text.resize(end + 1);
    const bool backslash = text.back() == '\\';
    if (backslash) text.pop_back();
    std::vector<std::string> pieces = Split(text, ';');
    for (size_t p = 0; p < pieces.size(); ++p) {
      if (p > 0 || !(continued || indented) || entries.empty()) {
        entries.push_back({block.LineOf(i), {}});
      }
      const std::vector<std::string> words = Words(pieces[p]);
      entries.back().words.insert(entries.back().words.end(), words.begin(), words.end());
    }
    continued = backslash;
  }
  for (Entry& entry : entries) {
    std::vector<std::string> joined;
    for (size_t w = 0; w < entry.words.size(); ++w) {
      if (entry.words[w] == "|" && !joined.empty() && w + 1 < entry.words.size()) {
        joined.back() += "|" + entry.words[++w];
      } else {
        joined.push_back(entry.words[w]);
      }
    }
    entry.words = joined;
  }
  return entries;
}

// The option a synopsis word shows (`[--seed` -> `--seed`, `--out=DIR` -> `--out`), or "".
std::string OptionOf(const std::string& word) {
  static const std::regex kOption(R"(^[\[(]*(--?[A-Za-z][A-Za-z0-9-]*)([\]),=].*)?$)");
  std::smatch match;
  if (!std::regex_match(word, match, kOption)) return "";
  const std::string option = match[1].str();
  // A short option is one letter; `-1|0|1` and the like are values.
  if (option.rfind("--", 0) != 0 && option.size() != 2) return "";
  return option;
}

std::string Joined(const std::vector<std::string>& words) {
  std::string text;
  for (const std::string& word : words) text += (text.empty() ? "" : " ") + word;
  return text;
}

// Asks each program for its help once.
class HelpCache {
 public:
  explicit HelpCache(const std::map<std::string, std::string>& programs) : programs_(programs) {}

  // The help of `command` (the program's name, then subcommands), or the failure to get it.
  const HelpText* Get(const std::vector<std::string>& command, std::string* failure) {
    const std::string key = Joined(command);
    if (const auto it = helps_.find(key); it != helps_.end()) return &it->second;
    std::vector<std::string> argv = {programs_.at(command[0])};
    argv.insert(argv.end(), command.begin() + 1, command.end());
    argv.push_back("--help");
    const process::CommandResult result = process::RunCommand(argv);
    if (result.exit_code != 0) {
      *failure = "`" + key + " --help` exited " + std::to_string(result.exit_code) + ": " +
                 result.output();
      return nullptr;
    }
    return &helps_.emplace(key, ParseHelp(result.out)).first->second;
  }

 private:
  const std::map<std::string, std::string>& programs_;
  std::map<std::string, HelpText> helps_;
};

std::vector<std::string> CheckEntry(const DocBlock& block, const Entry& entry, HelpCache& helps,
                                    const std::map<std::string, std::string>& programs) {
  const std::string where = block.file + ":" + std::to_string(entry.line) + ": ";
  const std::string program = std::filesystem::path(entry.words[0]).filename().string();
  if (programs.count(program) == 0) {
    std::string known;
    for (const auto& [name, path] : programs) known += (known.empty() ? "" : ", ") + name;
    return {where + "`" + entry.words[0] + "` is not a program the test knows (" + known + ")"};
  }
  std::vector<std::string> failures;
  std::string failure;
  // Every command the entry may mean: the program, then a subcommand per level (a|b: both).
  std::vector<std::vector<std::string>> commands = {{program}};
  size_t w = 1;
  for (; w < entry.words.size(); ++w) {
    const std::string& word = entry.words[w];
    if (word.empty() || word[0] == '-' || word[0] == '[' || word == "...") break;
    std::vector<std::vector<std::string>> deeper;
    for (const std::vector<std::string>& command : commands) {
      const HelpText* help = helps.Get(command, &failure);
      if (help == nullptr) return {where + failure};
      if (help->subcommands.empty()) break;  // a positional argument
      for (const std::string& name : Split(word, '|')) {
        if (!Contains(help->subcommands, name)) {
          failures.push_back(where + "`" + Joined(command) + "` has no subcommand " + name);
          continue;
        }
        std::vector<std::string> sub = command;
        sub.push_back(name);
        deeper.push_back(sub);
      }
    }
    if (deeper.empty()) break;
    commands = deeper;
  }
  // Options of a subcommand that does not exist say nothing more.
  if (!failures.empty()) return failures;
  for (; w < entry.words.size(); ++w) {
    const std::string option = OptionOf(entry.words[w]);
    if (option.empty()) continue;
    for (const std::vector<std::string>& command : commands) {
      const HelpText* help = helps.Get(command, &failure);
      if (help == nullptr) return {where + failure};
      if (!Contains(help->options, option)) {
        failures.push_back(where + "`" + Joined(command) + "` has no option " + option +
                           " (not in its --help)");
      }
    }
  }
  return failures;
}

}  // namespace

HelpText ParseHelp(const std::string& help) {
  // A name, then what CLI11 may glue to it: a flag's default (`--no-compare{false}`).
  static const std::regex kName(R"(^--?[A-Za-z0-9][A-Za-z0-9_-]*)");
  HelpText text;
  bool in_subcommands = false;
  std::istringstream in(help);
  for (std::string line; std::getline(in, line);) {
    const std::vector<std::string> words = Words(line);
    if (words.empty()) {
      in_subcommands = false;
      continue;
    }
    if (line[0] != ' ') {  // a section's title
      in_subcommands = line.rfind("Subcommands:", 0) == 0;
      continue;
    }
    if (in_subcommands) {
      text.subcommands.push_back(words[0]);
    } else if (words[0][0] == '-') {
      for (const std::string& name : Split(words[0], ',')) {
        std::smatch match;
        if (std::regex_search(name, match, kName)) text.options.push_back(match[0].str());
      }
    }
  }
  return text;
}

std::vector<std::string> CheckSynopsis(const DocBlock& block,
                                       const std::map<std::string, std::string>& programs) {
  HelpCache helps(programs);
  std::vector<std::string> failures;
  for (const Entry& entry : Entries(block)) {
    const std::vector<std::string> found = CheckEntry(block, entry, helps, programs);
    failures.insert(failures.end(), found.begin(), found.end());
  }
  return failures;
}

}  // namespace fleetmap::docs
