#pragma once

// One job's progress line on a stream, readable on a terminal and in a log alike (issue 33).
//
// On a terminal the line is rewritten in place: '\r', the text, and blanks over whatever a longer
// previous text left. A log file, a pipe or the systemd journal has no cursor to go back with, so
// '\r' updates there run together into one endless line; there each update written is a whole
// line, and at most one per `log_period` (the first always), so a log shows a long job moving
// without filling up. Finish() ends the job's line with its last state in both modes.
//
//   ProgressLine progress = ProgressLine::OnStderr();
//   for (...) progress.Update(fmt::format("[tiles wire] {} / {} s", done, total));
//   progress.Finish();
//
// Texts are single lines; their width on a terminal is counted in bytes (the house's texts are
// ASCII). Nothing else should write to the stream while a terminal line is open (between the
// first update and Finish()), or it lands on the progress line: Print() a message, or Finish()
// first.
//
// Thread-safety: one thread calls everything (a job's progress callback).

#include <chrono>
#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>

namespace fleetmap {

struct ProgressLineOptions {
  using Clock = std::chrono::steady_clock;

  bool terminal = false;  // rewrite one line in place (else whole lines, throttled)
  // Not on a terminal: a new line at most this often (updates in between are held back).
  Clock::duration log_period = std::chrono::seconds(10);
  // On a terminal: a redraw at most this often; zero redraws every update.
  Clock::duration terminal_period = Clock::duration::zero();
  // The time the periods are measured in; a test steps a clock of its own instead of sleeping.
  std::function<Clock::time_point()> now = [] { return Clock::now(); };
};

class ProgressLine {
 public:
  using Clock = ProgressLineOptions::Clock;

  ProgressLine(std::ostream& out, ProgressLineOptions options);
  // On std::cerr, rewritten in place when stderr is a terminal (`options.terminal` is replaced).
  static ProgressLine OnStderr(ProgressLineOptions options = {});
  // Whether stderr is a terminal: for commands that take their error stream as an argument and
  // carry this decision in their options.
  static bool StderrIsTerminal();

  // Ends a line left open on a terminal, so that what is written next starts on a line of its
  // own (an error path that returns early); held-back updates are not written.
  ~ProgressLine();
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  // The job's state now; written unless the last write was less than a period ago (held back
  // then, for Finish()).
  void Update(std::string_view text);
  // A state worth seeing whatever the period (a new stage): always written.
  void Milestone(std::string_view text);
  // A line of its own amid the updates (a warning about one item): on a terminal the open
  // progress line is ended first, and the next update starts below the message.
  void Print(std::string_view message);
  // Ends the line; the update held back last, if any, is written first. A later update starts a
  // new line, as for a new job.
  void Finish();
  // Ends the line with `text`, the job's final state, always written.
  void Finish(std::string_view text);

  bool terminal() const { return options_.terminal; }

 private:
  void Write(std::string_view text, Clock::time_point now);
  void EndLine();

  std::ostream& out_;
  const ProgressLineOptions options_;
  std::optional<Clock::time_point> last_write_;  // since the line began; none: nothing yet
  std::optional<std::string> held_;              // the newest update not written yet
  size_t drawn_width_ = 0;                       // terminal: of the text on the open line
  bool open_ = false;                            // terminal: a line drawn and not yet ended
};

}  // namespace fleetmap
