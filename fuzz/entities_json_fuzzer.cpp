// Fuzz target: an entities.json file (`fleetmap extrapolate --entities`, the agent's
// --entities): nlohmann's parser, then the strict-file, lenient-entry reader. What it keeps must
// write back as JSON that reads to the same number of entities without a warning.

#include <cstddef>
#include <cstdint>

#include "common/core/check.hpp"
#include "common/extrapolation/entities_json.hpp"
#include "fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace fleetmap;
  const StatusOr<extrapolation::ParsedEntities> parsed =
      extrapolation::ParseEntitiesJson(fuzz::AsText(data, size), "fuzz.json");
  if (!parsed.ok()) return 0;
  const std::string again = extrapolation::EntitiesToJson(parsed->entities);
  const StatusOr<extrapolation::ParsedEntities> back =
      extrapolation::ParseEntitiesJson(again, "re-written");
  FLEETMAP_CHECK(back.ok(), back.status().message());
  FLEETMAP_CHECK(back->warnings.empty(), back->warnings.front());
  return 0;
}
