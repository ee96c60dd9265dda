#include "common/store/store_options.hpp"

#include <string>

namespace fleetmap::store {

Status StoreOptions::Validate() const {
  if (max_history_rows < 0) {
    return InvalidArgumentError("store options: max_history_rows " +
                                std::to_string(max_history_rows) +
                                " is negative (0 means unlimited)");
  }
  if (busy_timeout_ms < 0) {
    return InvalidArgumentError("store options: busy_timeout_ms " +
                                std::to_string(busy_timeout_ms) + " is negative");
  }
  if (max_page_count < 0) {
    return InvalidArgumentError("store options: max_page_count " + std::to_string(max_page_count) +
                                " is negative (0 means no cap)");
  }
  if (lock_timeout_ms < 0) {
    return InvalidArgumentError("store options: lock_timeout_ms " +
                                std::to_string(lock_timeout_ms) + " is negative");
  }
  return Status::Ok();
}

void StoreOptions::Describe(OptionsPrinter& out) const {
  out.Add("keep_history", keep_history);
  out.Add("max_history_rows", max_history_rows);
  out.Add("busy_timeout_ms", busy_timeout_ms);
  out.Add("synchronous_full", synchronous_full);
  out.Add("verify_on_open", verify_on_open);
  out.Add("max_page_count", max_page_count);
  out.Add("lock_timeout_ms", lock_timeout_ms);
}

}  // namespace fleetmap::store
