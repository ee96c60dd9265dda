#include "common/core/progress_line.hpp"

#include <unistd.h>

#include <iostream>
#include <utility>

#include "common/core/check.hpp"

namespace fleetmap {

ProgressLine::ProgressLine(std::ostream& out, ProgressLineOptions options)
    : out_(out), options_(std::move(options)) {
  FLEETMAP_CHECK(options_.log_period >= Clock::duration::zero(), "ProgressLine: log_period < 0");
  FLEETMAP_CHECK(options_.terminal_period >= Clock::duration::zero(),
                 "ProgressLine: terminal_period < 0");
  FLEETMAP_CHECK(options_.now != nullptr, "ProgressLine: no clock");
}

ProgressLine ProgressLine::OnStderr(ProgressLineOptions options) {
  options.terminal = StderrIsTerminal();
  return ProgressLine(std::cerr, std::move(options));
}

bool ProgressLine::StderrIsTerminal() { return isatty(STDERR_FILENO) != 0; }

ProgressLine::~ProgressLine() {
  if (open_) EndLine();
}

void ProgressLine::Update(std::string_view text) {
  const Clock::time_point now = options_.now();
  const Clock::duration period = options_.terminal ? options_.terminal_period : options_.log_period;
  if (last_write_ && now - *last_write_ < period) {
    held_ = std::string(text);
    return;
  }
  Write(text, now);
}

void ProgressLine::Milestone(std::string_view text) { Write(text, options_.now()); }

void ProgressLine::Print(std::string_view message) {
  if (open_) EndLine();
  out_ << message << '\n';
  out_.flush();
}

void ProgressLine::Finish() {
  if (held_) {
    const std::string text = std::move(*held_);
    Write(text, options_.now());
  }
  if (open_) EndLine();
  last_write_.reset();
}

void ProgressLine::Finish(std::string_view text) {
  Write(text, options_.now());
  if (open_) EndLine();
  last_write_.reset();
}

void ProgressLine::Write(std::string_view text, Clock::time_point now) {
  // A newline in a text would break both the in-place redraw and the one-line-per-update log.
  FLEETMAP_CHECK(text.find_first_of("\r\n") == std::string_view::npos,
                 "ProgressLine: a progress text is one line");
  if (options_.terminal) {
    out_ << '\r' << text;
    if (text.size() < drawn_width_) out_ << std::string(drawn_width_ - text.size(), ' ');
    drawn_width_ = text.size();
    open_ = true;
  } else {
    out_ << text << '\n';
  }
  out_.flush();
  last_write_ = now;
  held_.reset();
}

void ProgressLine::EndLine() {
  out_ << '\n';
  out_.flush();
  drawn_width_ = 0;
  open_ = false;
}

}  // namespace fleetmap
