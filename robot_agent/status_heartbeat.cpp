#include "robot_agent/status_heartbeat.hpp"

#include <spdlog/spdlog.h>

namespace fleetmap::agent {

Status StatusHeartbeat::Start(const RobotStatus& first) {
  robot_ = first.robot;
  Update(first);
  FLEETMAP_RETURN_IF_ERROR(WriteNow());
  thread_.Start([this] {
    std::lock_guard lock(write_mutex_);
    const auto now = std::chrono::steady_clock::now();
    if (now - last_write_ < period_) return false;
    bool hung;
    {
      std::lock_guard latest_lock(mutex_);
      hung = now - last_update_ > hung_after_;
    }
    if (hung != hung_) {
      hung_ = hung;
      if (hung) {
        spdlog::error(
            "{}: the agent's loop has not run for {} ms: no status until it does (the "
            "server reports the robot lost)",
            robot_.value, hung_after_.count());
      } else {
        spdlog::info("{}: the agent's loop runs again", robot_.value);
      }
    }
    if (hung) return false;
    if (const Status written = Write(); !written.ok()) {
      spdlog::warn("{}: {}", robot_.value, written.message());
    }
    return false;
  });
  return Status::Ok();
}

void StatusHeartbeat::Update(const RobotStatus& status) {
  std::lock_guard lock(mutex_);
  const auto sequence = latest_.sequence_number;
  latest_ = status;
  latest_.sequence_number = sequence;
  last_update_ = std::chrono::steady_clock::now();
}

Status StatusHeartbeat::WriteNow() {
  std::lock_guard lock(write_mutex_);
  return Write();
}

Status StatusHeartbeat::Write() {
  RobotStatus status;
  {
    std::lock_guard lock(mutex_);
    latest_.stamp = Clock::now();
    ++latest_.sequence_number;
    status = latest_;
  }
  last_write_ = std::chrono::steady_clock::now();
  return writer_.Write(status);
}

}  // namespace fleetmap::agent
