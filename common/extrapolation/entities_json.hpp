#pragma once

// The entities JSON file (docs/extrapolation.md): {"entities": [{"class": "door" | "stairs" |
// "person", "id": ..., ...}, ...]}. Parsing is strict about the file and lenient about single
// entries: a file that is not JSON, whose top level is not an object, or that has no "entities"
// array is an error; an entry that is unusable (unknown class, missing or mistyped field, a
// non-finite number, a door of (near) zero width, a track of fewer than two points, a duplicate
// id) is skipped with a warning naming it and what is wrong, and the rest of the file is used.
// Unknown keys are ignored with a warning.
//
// Thread-safety: stateless.

#include <string>
#include <string_view>
#include <vector>

#include "common/core/status.hpp"
#include "common/scene/entities.hpp"

namespace fleetmap::extrapolation {

struct ParsedEntities {
  scene::Entities entities;
  std::vector<std::string> warnings;  // one per skipped entry or ignored key, naming it
};

// Errors (kInvalidArgument) start with `source_name`: not JSON, top level not an object, no
// "entities" array.
StatusOr<ParsedEntities> ParseEntitiesJson(std::string_view text, std::string_view source_name);

// The JSON text of `entities` (reads back with ParseEntitiesJson to the same entities).
std::string EntitiesToJson(const scene::Entities& entities);

}  // namespace fleetmap::extrapolation
