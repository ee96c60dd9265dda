#pragma once

#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include "common/core/sample_queue.hpp"
#include "common/core/wake_up.hpp"
#include "common/core/worker_thread.hpp"
#include "common/registration/placer.hpp"

namespace fleetmap::server {

// Runs the fleet map's registrations on a thread of their own: one takes up to seconds and must
// not hold back fusion. One job at a time (the placer hands out the next once this one's result
// was taken). Submit() and Results() from the fusion worker's thread; `done` is woken when a
// result is ready.
class RegistrationRunner {
 public:
  RegistrationRunner(const registration::RegistrationOptions& options,
                     std::shared_ptr<WakeUp> done);
  ~RegistrationRunner();
  RegistrationRunner(const RegistrationRunner&) = delete;
  RegistrationRunner& operator=(const RegistrationRunner&) = delete;

  void Submit(registration::PlacementJob job);
  std::vector<registration::PlacementResult> Results() { return results_.Drain(); }

 private:
  void Work();

  registration::RegistrationOptions options_;
  std::shared_ptr<WakeUp> done_;
  std::mutex mutex_;
  std::optional<registration::PlacementJob> pending_;  // guarded by mutex_
  SampleQueue<registration::PlacementResult> results_{64};
  WorkerThread thread_{std::nullopt};  // last: stops before the rest goes
};

}  // namespace fleetmap::server
