// Child process of the crash tests: commits WriterBatch(0), WriterBatch(1), ... to a map store and
// prints "committed <batch>" after each commit returned, until killed. With `batches`, it stops
// after that many and waits to be killed: the write-ahead log then holds exactly those commits,
// however slowly the test gets round to killing it (no checkpoint can have reset it meanwhile).
// Usage: store_writer_helper <database> [batches]

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#include "common/store/map_store.hpp"
#include "tests/unit/store/writer_batches.hpp"

int main(int argc, char** argv) {
  if (argc < 2 || argc > 3) {
    std::fprintf(stderr, "usage: %s <database> [batches]\n", argv[0]);
    return 2;
  }
  const int max_batches = argc == 3 ? std::atoi(argv[2]) : 100000;
  auto store = fleetmap::store::MapStore::Open(argv[1]);
  if (!store.ok()) {
    std::fprintf(stderr, "%s\n", store.status().ToString().c_str());
    return 1;
  }
  for (int batch = 0; batch < max_batches; ++batch) {
    const fleetmap::Status status =
        (*store)->PutTiles(fleetmap::store::testing::WriterBatch(batch));
    if (!status.ok()) {
      std::fprintf(stderr, "%s\n", status.ToString().c_str());
      return 1;
    }
    std::printf("committed %d\n", batch);
    std::fflush(stdout);
  }
  for (;;) pause();  // until killed, the store left open
}
