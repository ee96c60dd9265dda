#include "server/registration_runner.hpp"

namespace fleetmap::server {

RegistrationRunner::RegistrationRunner(const registration::RegistrationOptions& options,
                                       std::shared_ptr<WakeUp> done)
    : options_(options), done_(std::move(done)) {
  thread_.Start([this] {
    Work();
    return false;
  });
}

RegistrationRunner::~RegistrationRunner() { thread_.Stop(); }

void RegistrationRunner::Submit(registration::PlacementJob job) {
  {
    std::lock_guard lock(mutex_);
    pending_ = std::move(job);
  }
  thread_.Wake();
}

void RegistrationRunner::Work() {
  std::optional<registration::PlacementJob> job;
  {
    std::lock_guard lock(mutex_);
    job.swap(pending_);
  }
  if (!job) return;
  results_.Push(registration::RunPlacementJob(*std::move(job), options_));
  if (done_) done_->Notify();
}

}  // namespace fleetmap::server
