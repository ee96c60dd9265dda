#include "tests/architecture/include_rules.hpp"

#include <fstream>
#include <regex>
#include <sstream>

namespace fleetmap::architecture {
namespace {

namespace fs = std::filesystem;

const std::regex kGeneratedHeader(R"(^[a-z_]+/(msg|srv)/)");
const std::regex kProjectInclude(R"re(^\s*#\s*include\s*"([^"]+)")re");

std::vector<std::string> Words(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> words;
  for (std::string word; in >> word;) words.push_back(word);
  return words;
}

bool IsSource(const fs::path& path) {
  const std::string ext = path.extension().string();
  return ext == ".hpp" || ext == ".cpp" || ext == ".h" || ext == ".cxx";
}

bool Starts(const std::string& text, const std::string& prefix) {
  return text.compare(0, prefix.size(), prefix) == 0;
}

// The module a repository path belongs to, or "" for none (a file at the top, tests/...).
std::string ModuleOf(const std::string& path) {
  const size_t first = path.find('/');
  if (first == std::string::npos) return "";
  const std::string top = path.substr(0, first);
  if (top == "common" || top == "bench" || top == "cli") {
    const size_t second = path.find('/', first + 1);
    return second == std::string::npos ? top : path.substr(0, second);
  }
  return top;
}

bool IsException(const std::string& file, const IncludeRules& rules) {
  for (const std::string& allowed : rules.edge_exceptions) {
    if (allowed.back() == '/' ? Starts(file, allowed) : file == allowed) return true;
  }
  return false;
}

// Why `file` (in `module`, "" for tests) may not include `include`, or "" when it may.
std::string Check(const std::string& file, const std::string& module, const std::string& include,
                  const IncludeRules& rules, const std::set<std::string>& project_tops) {
  if (std::regex_search(include, kGeneratedHeader)) {
    if (module == "common/transport" || IsException(file, rules)) return "";
    return "generated DDS types stay in common/transport";
  }
  const std::string target = ModuleOf(include);
  if (target.empty() || target == module) return "";
  if (project_tops.count(target.substr(0, target.find('/'))) == 0) return "";  // a library's
  if (include.find("/internal/") != std::string::npos && !IsException(file, rules)) {
    return "internal/ headers are private to " + target;
  }
  if (Starts(file, "tests/")) return "";
  const auto allowed = rules.may_include.find(module);
  if (allowed != rules.may_include.end() && allowed->second.count(target) > 0) return "";
  return module + " may not include " + target + " (docs/architecture.md)";
}

}  // namespace

StatusOr<IncludeRules> ReadIncludeRules(const fs::path& markdown) {
  std::ifstream in(markdown);
  if (!in) return NotFoundError(markdown.string() + ": cannot open");
  IncludeRules rules;
  bool in_block = false;
  bool found = false;
  int line_number = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_number;
    if (!in_block) {
      if (Starts(line, "```include-rules")) in_block = found = true;
      continue;
    }
    if (Starts(line, "```")) break;
    const std::vector<std::string> words = Words(line.substr(0, line.find('#')));
    if (words.empty()) continue;
    const std::string where = markdown.string() + ":" + std::to_string(line_number);
    if (words[0] == "edge-exception") {
      rules.edge_exceptions.insert(rules.edge_exceptions.end(), words.begin() + 1, words.end());
    } else if (words.size() >= 2 && words[1] == "->") {
      if (rules.may_include.count(words[0]) > 0) {
        return InvalidArgumentError(where + ": module " + words[0] + " listed twice");
      }
      rules.may_include[words[0]] = std::set<std::string>(words.begin() + 2, words.end());
    } else {
      return InvalidArgumentError(where + ": expected '<module> -> <modules>' or " +
                                  "'edge-exception <paths>', got '" + line + "'");
    }
  }
  if (!found) return InvalidArgumentError(markdown.string() + ": no ```include-rules block");
  return rules;
}

std::vector<IncludeViolation> CheckIncludes(const fs::path& root, const IncludeRules& rules) {
  std::vector<IncludeViolation> violations;
  std::set<std::string> tops = {"tests"};
  for (const auto& [module, allowed] : rules.may_include) {
    tops.insert(module.substr(0, module.find('/')));
  }
  for (const std::string& top : tops) {
    if (!fs::is_directory(root / top)) continue;
    for (const auto& entry : fs::recursive_directory_iterator(root / top)) {
      if (!entry.is_regular_file() || !IsSource(entry.path())) continue;
      const std::string file = fs::relative(entry.path(), root).generic_string();
      if (Starts(file, "tests/data/")) continue;  // fixtures, not code
      const std::string module = Starts(file, "tests/") ? "" : ModuleOf(file);
      if (!module.empty() && rules.may_include.count(module) == 0) {
        violations.push_back({file, 0, "", "module " + module + " is not in the rules"});
        continue;
      }
      std::ifstream in(entry.path());
      int line_number = 0;
      std::smatch match;
      for (std::string line; std::getline(in, line);) {
        ++line_number;
        if (!std::regex_search(line, match, kProjectInclude)) continue;
        const std::string include = match[1];
        const std::string why = Check(file, module, include, rules, tops);
        if (!why.empty()) violations.push_back({file, line_number, include, why});
      }
    }
  }
  return violations;
}

}  // namespace fleetmap::architecture
