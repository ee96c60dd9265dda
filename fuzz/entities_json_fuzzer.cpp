// Fuzz target: an entities.json file (`fleetmap extrapolate --entities`, the agent's
// --entities): nlohmann's parser, then the strict-file, lenient-entry reader. What it keeps must
// write back as JSON that reads to the same entities, none skipped (a warning that only says what
// was inferred, such as a door's zero opening direction, is allowed).

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
  FLEETMAP_CHECK(back->entities.doors.size() == parsed->entities.doors.size() &&
                     back->entities.stairs.size() == parsed->entities.stairs.size() &&
                     back->entities.people.size() == parsed->entities.people.size(),
                 "an entity was skipped on a round trip");
  return 0;
}
