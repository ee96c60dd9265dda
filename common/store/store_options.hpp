#pragma once

#include <cstdint>

#include "common/core/options_printer.hpp"
#include "common/core/status.hpp"

namespace fleetmap::store {

// How a MapStore keeps its data. Validated once by MapStore::Open.
//
// Durability: the database runs in WAL mode. With `synchronous_full = false` (SQLite's
// synchronous=NORMAL) a commit is written to the WAL file but not fsynced: it survives the server
// process being killed (SIGKILL, crash), because the bytes are already in the kernel's page cache,
// but the last commits may be lost on power loss or a kernel crash (the database stays consistent).
// `synchronous_full = true` fsyncs the WAL on every commit: durable on power loss too, at the cost
// of one fsync per PutTiles batch.
struct StoreOptions {
  // Append every tile revision to the history table (the object learner's input).
  bool keep_history = true;
  // Keep at most this many history rows, dropping the oldest first; 0: unlimited.
  int64_t max_history_rows = 0;
  // How long a statement waits for a lock held by another connection before failing.
  int busy_timeout_ms = 2000;
  // fsync the WAL on every commit (see above).
  bool synchronous_full = false;
  // Run PRAGMA quick_check on open (reads the whole file: O(size) start-up time).
  bool verify_on_open = true;
  // Caps the database file at this many pages (PRAGMA max_page_count; 0: SQLite's default, no
  // practical cap). A write that needs more fails like a full disk (kResourceExhausted) until
  // rows are deleted. Tests use it to simulate a full disk.
  int64_t max_page_count = 0;
  // How long Open waits for another writer to release the store's lock (StoreLock) before it
  // fails; 0: fail at once.
  int64_t lock_timeout_ms = 0;

  Status Validate() const;
  void Describe(OptionsPrinter& out) const;
};

}  // namespace fleetmap::store
