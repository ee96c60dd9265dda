#pragma once

// A real browser for the web view's tests: Debian's chromium, headless, driven through the Chrome
// DevTools Protocol over --remote-debugging-pipe (file descriptors 3 and 4, messages ended by a
// NUL byte), so no WebDriver or npm package is needed. Enough of the protocol to load a page, read
// what it shows (Runtime.evaluate) and take a screenshot.

#include <sys/types.h>

#include <chrono>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "common/core/status.hpp"

namespace fleetmap::testing {

class HeadlessChromium {
 public:
  // Starts /usr/bin/chromium (or $FLEETMAP_CHROMIUM) with a fresh profile and opens `url`.
  static StatusOr<std::unique_ptr<HeadlessChromium>> Open(const std::string& url, int width = 1400,
                                                          int height = 900);
  ~HeadlessChromium();
  HeadlessChromium(const HeadlessChromium&) = delete;
  HeadlessChromium& operator=(const HeadlessChromium&) = delete;

  // The value of a JavaScript expression in the page (returnByValue); errors carry the page's
  // exception text.
  StatusOr<nlohmann::json> Evaluate(const std::string& expression);
  // Polls `expression` until it is true or `timeout` passes; the last value on timeout.
  StatusOr<nlohmann::json> WaitFor(const std::string& expression,
                                   std::chrono::milliseconds timeout);
  // A PNG of the page's viewport.
  Status Screenshot(const std::string& png_path);

 private:
  HeadlessChromium() = default;
  // Sends one command (to the page's session unless `browser_level`) and waits for its answer.
  StatusOr<nlohmann::json> Call(const std::string& method, nlohmann::json params,
                                bool browser_level = false);
  StatusOr<std::string> ReadMessage(std::chrono::milliseconds timeout);

  pid_t pid_ = -1;
  int to_browser_ = -1;
  int from_browser_ = -1;
  std::string pending_;  // bytes read past the last whole message
  std::string session_id_;
  std::string profile_dir_;
  int next_id_ = 1;
};

}  // namespace fleetmap::testing
