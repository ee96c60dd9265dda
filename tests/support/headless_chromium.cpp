#include "tests/support/headless_chromium.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <thread>
#include <vector>

namespace fleetmap::testing {
namespace {

using nlohmann::json;
using Clock = std::chrono::steady_clock;

constexpr std::chrono::seconds kCallTimeout{30};

std::string Base64Decode(const std::string& text) {
  static const std::string kAlphabet =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  int value = 0;
  int bits = -8;
  for (char c : text) {
    const size_t index = kAlphabet.find(c);
    if (index == std::string::npos) continue;  // padding
    value = (value << 6) + static_cast<int>(index);
    bits += 6;
    if (bits >= 0) {
      out.push_back(static_cast<char>((value >> bits) & 0xFF));
      bits -= 8;
    }
  }
  return out;
}

}  // namespace

StatusOr<std::unique_ptr<HeadlessChromium>> HeadlessChromium::Open(const std::string& url,
                                                                   int width, int height) {
  const char* from_environment = std::getenv("FLEETMAP_CHROMIUM");
  const std::string binary = from_environment != nullptr ? from_environment : "/usr/bin/chromium";
  if (::access(binary.c_str(), X_OK) != 0) {
    return NotFoundError(binary + " is not installed (scripts/install-deps.sh installs chromium)");
  }
  std::unique_ptr<HeadlessChromium> browser(new HeadlessChromium());
  browser->profile_dir_ =
      (std::filesystem::temp_directory_path() /
       ("fleetmap_chromium_" + std::to_string(getpid()) + "_" + std::to_string(rand())))
          .string();
  std::filesystem::create_directories(browser->profile_dir_);
  int to_browser[2];
  int from_browser[2];
  if (::pipe2(to_browser, O_CLOEXEC) != 0 || ::pipe2(from_browser, O_CLOEXEC) != 0) {
    return InternalError("pipe failed");
  }
  const std::vector<std::string> args = {
      binary,
      "--headless=new",
      "--remote-debugging-pipe",
      "--no-sandbox",  // tests may run as root
      "--disable-gpu",
      "--no-first-run",
      "--no-default-browser-check",
      "--user-data-dir=" + browser->profile_dir_,
      "--window-size=" + std::to_string(width) + "," + std::to_string(height),
      url};
  const pid_t pid = ::fork();
  if (pid < 0) return InternalError("fork failed");
  if (pid == 0) {
    // The browser reads commands on fd 3 and writes answers on fd 4. Both ends move above 4
    // first, so that neither dup2 overwrites the other (a pipe may itself be fd 3 or 4).
    const int commands = ::fcntl(to_browser[0], F_DUPFD, 10);
    const int answers = ::fcntl(from_browser[1], F_DUPFD, 10);
    ::dup2(commands, 3);
    ::dup2(answers, 4);
    const int quiet = ::open("/dev/null", O_WRONLY);
    ::dup2(quiet, 1);
    ::dup2(quiet, 2);
    std::vector<char*> argv;
    for (const std::string& arg : args) argv.push_back(const_cast<char*>(arg.c_str()));
    argv.push_back(nullptr);
    ::execv(binary.c_str(), argv.data());
    ::_exit(127);
  }
  ::close(to_browser[0]);
  ::close(from_browser[1]);
  browser->pid_ = pid;
  browser->to_browser_ = to_browser[1];
  browser->from_browser_ = from_browser[0];

  // Attach to the page the browser opened with `url`.
  const auto deadline = Clock::now() + kCallTimeout;
  while (Clock::now() < deadline) {
    FLEETMAP_ASSIGN_OR_RETURN(json targets, browser->Call("Target.getTargets", json::object(),
                                                          /*browser_level=*/true));
    for (const json& target : targets["targetInfos"]) {
      if (target["type"] != "page") continue;
      FLEETMAP_ASSIGN_OR_RETURN(
          json attached,
          browser->Call("Target.attachToTarget",
                        {{"targetId", target["targetId"]}, {"flatten", true}}, true));
      browser->session_id_ = attached["sessionId"];
      FLEETMAP_RETURN_IF_ERROR(browser->Call("Runtime.enable", json::object()).status());
      return browser;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  return UnavailableError("chromium opened no page for " + url);
}

HeadlessChromium::~HeadlessChromium() {
  if (to_browser_ >= 0) ::close(to_browser_);  // the browser quits when its pipe closes
  if (from_browser_ >= 0) ::close(from_browser_);
  if (pid_ > 0) {
    const auto deadline = Clock::now() + std::chrono::seconds(5);
    int status = 0;
    while (::waitpid(pid_, &status, WNOHANG) == 0) {
      if (Clock::now() > deadline) {
        ::kill(pid_, SIGKILL);
        ::waitpid(pid_, &status, 0);
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  }
  std::error_code ignored;
  std::filesystem::remove_all(profile_dir_, ignored);
}

StatusOr<std::string> HeadlessChromium::ReadMessage(std::chrono::milliseconds timeout) {
  const auto deadline = Clock::now() + timeout;
  while (true) {
    if (const size_t end = pending_.find('\0'); end != std::string::npos) {
      std::string message = pending_.substr(0, end);
      pending_.erase(0, end + 1);
      return message;
    }
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
    if (left <= 0) return UnavailableError("chromium did not answer in time");
    pollfd ready{from_browser_, POLLIN, 0};
    if (::poll(&ready, 1, static_cast<int>(left)) <= 0) continue;
    char buffer[65536];
    const ssize_t n = ::read(from_browser_, buffer, sizeof(buffer));
    if (n <= 0) return UnavailableError("chromium closed its pipe (did it crash?)");
    pending_.append(buffer, static_cast<size_t>(n));
  }
}

StatusOr<json> HeadlessChromium::Call(const std::string& method, json params, bool browser_level) {
  const int id = next_id_++;
  json command = {{"id", id}, {"method", method}, {"params", std::move(params)}};
  if (!browser_level) command["sessionId"] = session_id_;
  std::string wire = command.dump();
  wire.push_back('\0');
  for (size_t sent = 0; sent < wire.size();) {
    const ssize_t n = ::write(to_browser_, wire.data() + sent, wire.size() - sent);
    if (n <= 0) return UnavailableError("cannot write to chromium's pipe");
    sent += static_cast<size_t>(n);
  }
  const auto deadline = Clock::now() + kCallTimeout;
  while (Clock::now() < deadline) {
    FLEETMAP_ASSIGN_OR_RETURN(std::string text,
                              ReadMessage(std::chrono::duration_cast<std::chrono::milliseconds>(
                                  deadline - Clock::now())));
    const json answer = json::parse(text, nullptr, /*allow_exceptions=*/false);
    if (!answer.is_object() || !answer.contains("id") || answer["id"] != id) continue;  // events
    if (answer.contains("error")) {
      return InternalError(method + ": " + answer["error"].dump());
    }
    return answer["result"];
  }
  return UnavailableError(method + ": chromium did not answer in time");
}

StatusOr<json> HeadlessChromium::Evaluate(const std::string& expression) {
  FLEETMAP_ASSIGN_OR_RETURN(
      json result, Call("Runtime.evaluate", {{"expression", expression}, {"returnByValue", true}}));
  if (result.contains("exceptionDetails")) {
    return InvalidArgumentError(expression + ": " + result["exceptionDetails"].dump());
  }
  return result["result"].value("value", json(nullptr));
}

StatusOr<json> HeadlessChromium::WaitFor(const std::string& expression,
                                         std::chrono::milliseconds timeout) {
  const auto deadline = Clock::now() + timeout;
  json value;
  while (true) {
    auto evaluated = Evaluate(expression);
    if (evaluated.ok()) {
      value = *evaluated;
      if (value == true) return value;
    }
    if (Clock::now() >= deadline) {
      if (!evaluated.ok()) return evaluated.status();
      return value;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
}

Status HeadlessChromium::Screenshot(const std::string& png_path) {
  FLEETMAP_ASSIGN_OR_RETURN(json shot, Call("Page.captureScreenshot", {{"format", "png"}}));
  std::ofstream file(png_path, std::ios::binary);
  file << Base64Decode(shot["data"].get<std::string>());
  if (!file) return UnavailableError(png_path + ": cannot write the screenshot");
  return Status::Ok();
}

}  // namespace fleetmap::testing
