#include "tests/docs/block_runner.hpp"

#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <memory>
#include <optional>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "common/process/subprocess.hpp"

namespace fleetmap::docs {
namespace {

namespace fs = std::filesystem;
using std::chrono::milliseconds;

// setsid(1) makes the shell the leader of a new process group (its pid is the group's id): the
// group holds everything the block starts, however deep.
constexpr char kSetsid[] = "/usr/bin/setsid";
constexpr char kBash[] = "/bin/bash";
// What a plain block's ERR trap prints: the script line and the exit code of the command that
// failed, so that the failure can name the document's line.
constexpr char kFailedTag[] = "fleetmap-docs-test: failed at ";
constexpr size_t kOutputLines = 60;  // of a failing command's output, the last ones

std::string Quoted(const std::string& text) {
  std::string quoted = "'";
  for (const char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

std::string Seconds(milliseconds duration) {
  std::ostringstream text;
  text << static_cast<double>(duration.count()) / 1000.0 << " s";
  return text.str();
}

// The first line of every script, all on one line, so that the script's line N + 1 is the
// block's line N.
std::string Header(const fs::path& directory, bool stop_at_failure) {
  std::string header = "exec 2>&1; cd -- " + Quoted(directory.string()) + " || exit 97;";
  if (stop_at_failure) {
    header += " trap 'status=$?; echo \"" + std::string(kFailedTag) +
              "$LINENO $status\"' ERR; set -e -o pipefail;";
  }
  return header + "\n";
}

// The script in a temporary file outside the block's directory (which the block may list).
class ScriptFile {
 public:
  explicit ScriptFile(const std::string& text) {
    std::string path_template = (fs::temp_directory_path() / "fleetmap-docs-block-XXXXXX").string();
    const int fd = mkstemp(path_template.data());
    if (fd < 0) throw std::runtime_error("mkstemp failed for " + path_template);
    close(fd);
    path_ = path_template;
    std::ofstream(path_) << text;
  }
  ~ScriptFile() { std::remove(path_.c_str()); }
  ScriptFile(const ScriptFile&) = delete;
  ScriptFile& operator=(const ScriptFile&) = delete;

  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

// Orphans of a block (what its shell left running) become this process's children rather than
// init's, so that they can be reaped here and never linger as zombies of a test machine.
void BecomeSubreaper() { prctl(PR_SET_CHILD_SUBREAPER, 1); }

// Whether a process of `group` still runs (zombies do not count).
bool GroupAlive(pid_t group) {
  for (const auto& entry : fs::directory_iterator("/proc")) {
    const std::string name = entry.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream stat(entry.path() / "stat");
    std::string line;
    if (!std::getline(stat, line)) continue;  // gone meanwhile
    const size_t close = line.rfind(')');
    if (close == std::string::npos) continue;
    std::istringstream fields(line.substr(close + 2));
    std::string state;
    pid_t parent = 0;
    pid_t process_group = 0;
    fields >> state >> parent >> process_group;
    if (process_group == group && state != "Z" && state != "X") return true;
  }
  return false;
}

bool WaitGroupGone(pid_t group, milliseconds limit) {
  const auto deadline = std::chrono::steady_clock::now() + limit;
  while (GroupAlive(group)) {
    if (std::chrono::steady_clock::now() >= deadline) return false;
    std::this_thread::sleep_for(milliseconds(50));
  }
  return true;
}

// Stops what is left of `group`: SIGINT, as a reader's Ctrl-C, then SIGTERM, as `kill` (bash
// starts a script's background commands with SIGINT ignored, and a reader stops them with `kill
// %1`), each given `limit`, then SIGKILL. False if SIGKILL was needed.
bool StopGroup(pid_t group, milliseconds limit) {
  for (const int signal : {SIGINT, SIGTERM}) {
    if (!GroupAlive(group)) return true;
    kill(-group, signal);
    if (WaitGroupGone(group, limit)) return true;
  }
  kill(-group, SIGKILL);
  WaitGroupGone(group, std::chrono::seconds(5));
  return false;
}

// Reaps the group's orphans (this process is their subreaper); call once the group's leader was
// waited for, so that its exit code stays its Subprocess's.
void ReapGroup(pid_t group) {
  while (waitpid(-group, nullptr, WNOHANG) > 0) {
  }
}

std::unique_ptr<process::Subprocess> StartScript(const std::string& script_path,
                                                 const RunSettings& settings) {
  return std::make_unique<process::Subprocess>(
      std::vector<std::string>{kSetsid, kBash, "--noprofile", "--norc", script_path},
      settings.environment);
}

// The last kOutputLines lines of `output`, indented under the failure.
std::string Tail(const std::string& output) {
  std::vector<std::string> lines;
  std::istringstream in(output);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind(kFailedTag, 0) != 0) lines.push_back(line);
  }
  std::string tail;
  if (lines.size() > kOutputLines) {
    tail += "    ... (" + std::to_string(lines.size() - kOutputLines) + " lines before)\n";
  }
  for (size_t i = lines.size() > kOutputLines ? lines.size() - kOutputLines : 0; i < lines.size();
       ++i) {
    tail += "    | " + lines[i] + "\n";
  }
  return tail.empty() ? "    (no output)\n" : tail;
}

// The command of `block` that holds document line `line` (bash names a command's last line).
TypedCommand CommandAt(const DocBlock& block, int line) {
  TypedCommand found{line, "?"};
  for (const TypedCommand& command : TypedCommands(block)) {
    if (command.line <= line) found = command;
  }
  return found;
}

std::string Describe(const TypedCommand& command) { return "`" + command.text + "`"; }

}  // namespace

std::vector<std::string> RunBlock(const DocBlock& block, const RunSettings& settings) {
  BecomeSubreaper();
  std::string script = Header(settings.directory, /*stop_at_failure=*/true);
  for (const std::string& line : TypedLines(block)) script += line + "\n";
  const ScriptFile file(script);
  std::unique_ptr<process::Subprocess> shell = StartScript(file.path(), settings);
  if (!shell->started()) return {block.Where() + ": could not start " + kBash};

  std::vector<std::string> failures;
  const std::optional<int> exit_code = shell->Wait(settings.time_limit);
  if (!exit_code) {
    failures.push_back(block.Where() + ": not done within " + Seconds(settings.time_limit) +
                       " (the time limit of a block)\n" + Tail(shell->Output()));
  }
  const bool stopped = StopGroup(shell->pid(), settings.stop_limit);
  shell->Wait(std::chrono::seconds(5));
  ReapGroup(shell->pid());
  if (exit_code && *exit_code != 0) {
    const std::string output = shell->Output();
    static const std::regex kTag(std::string(kFailedTag) + R"(([0-9]+) ([0-9]+))");
    std::smatch tag;
    if (std::regex_search(output, tag, kTag)) {
      // Script line N + 1 is the block's line N (the header is line 1).
      const int line = block.LineOf(static_cast<size_t>(std::stoi(tag[1].str()) - 2));
      const TypedCommand command = CommandAt(block, line);
      failures.push_back(block.file + ":" + std::to_string(command.line) + ": exit " +
                         tag[2].str() + " from " + Describe(command) + "\n" + Tail(output));
    } else {
      failures.push_back(block.Where() + ": the block exited " + std::to_string(*exit_code) + "\n" +
                         Tail(output));
    }
  }
  if (!stopped) {
    failures.push_back(block.Where() + ": what it left running did not stop within " +
                       Seconds(settings.stop_limit) + " of SIGINT, nor of SIGTERM\n" +
                       Tail(shell->Output()));
  }
  return failures;
}

std::vector<std::string> RunLongRunning(const DocBlock& block, const RunSettings& settings) {
  BecomeSubreaper();
  // A reader starts each program in a terminal of its own, or puts it in the background; here
  // each runs alone, so a trailing `&` (before any comment) is dropped.
  static const std::regex kBackground(R"(\s&\s*(#.*)?$)");
  struct Program {
    TypedCommand command;
    std::unique_ptr<ScriptFile> script;
    std::unique_ptr<process::Subprocess> process;
    bool failed = false;
  };
  std::vector<Program> programs;
  for (const TypedCommand& command : TypedCommands(block)) {
    Program program{command, nullptr, nullptr, false};
    program.script =
        std::make_unique<ScriptFile>(Header(settings.directory, /*stop_at_failure=*/false) +
                                     std::regex_replace(command.text, kBackground, " $1") + "\n");
    program.process = StartScript(program.script->path(), settings);
    programs.push_back(std::move(program));
  }

  std::vector<std::string> failures;
  const auto hold = milliseconds(static_cast<int64_t>(block.hold_seconds * 1000.0));
  const auto deadline = std::chrono::steady_clock::now() + hold;
  for (Program& program : programs) {
    const auto left =
        std::chrono::duration_cast<milliseconds>(deadline - std::chrono::steady_clock::now());
    const std::optional<int> early = program.process->Wait(std::max(left, milliseconds(0)));
    if (early && *early != 0) {
      program.failed = true;
      failures.push_back(block.file + ":" + std::to_string(program.command.line) + ": exit " +
                         std::to_string(*early) + " from " + Describe(program.command) +
                         " within " + Seconds(hold) + " of its start\n" +
                         Tail(program.process->Output()));
    }
  }
  // Ctrl-C reaches the whole group: the shell and the program it waits for.
  for (Program& program : programs) {
    if (!program.process->Wait(milliseconds(0))) kill(-program.process->pid(), SIGINT);
  }
  for (Program& program : programs) {
    const pid_t group = program.process->pid();
    const std::optional<int> exit_code = program.process->Wait(settings.stop_limit);
    if (!exit_code) {
      failures.push_back(block.file + ":" + std::to_string(program.command.line) + ": " +
                         Describe(program.command) + " did not stop within " +
                         Seconds(settings.stop_limit) + " of SIGINT\n" +
                         Tail(program.process->Output()));
    } else if (*exit_code != 0 && !program.failed) {
      failures.push_back(block.file + ":" + std::to_string(program.command.line) + ": exit " +
                         std::to_string(*exit_code) + " from " + Describe(program.command) +
                         " on SIGINT\n" + Tail(program.process->Output()));
    }
    StopGroup(group, settings.stop_limit);
    program.process->Wait(std::chrono::seconds(5));
    ReapGroup(group);
  }
  return failures;
}

}  // namespace fleetmap::docs
