#include "common/core/worker_thread.hpp"

#include <utility>

namespace fleetmap {

void WorkerThread::Start(Round round, std::function<void()> at_stop) {
  round_ = std::move(round);
  at_stop_ = std::move(at_stop);
  thread_ = std::thread([this] { Loop(); });
}

void WorkerThread::Stop() {
  stop_.store(true);
  wake_up_->Notify();
  if (thread_.joinable()) thread_.join();
}

void WorkerThread::Loop() {
  bool work_left = false;
  while (!stop_.load()) {
    if (!work_left) {
      if (timeout_) {
        wake_up_->WaitFor(*timeout_);
      } else {
        wake_up_->Wait();
      }
    }
    work_left = round_();
  }
  if (at_stop_) at_stop_();
}

}  // namespace fleetmap
