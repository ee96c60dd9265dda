#pragma once

// The entities JSON file (docs/extrapolation.md): {"doors": [...], "stairs": [...],
// "people": [...]}. Parsing is strict about the file and lenient about single entries: a file
// that is not JSON, or whose top level is not an object of known arrays, is an error; an entry
// that is unusable (missing field, NaN, a zero-width door, a one-point track, an unknown class)
// is skipped with a warning naming it and what is wrong, and the rest of the file is used.
//
// Thread-safety: stateless.

#include <string>
#include <string_view>
#include <vector>

#include "common/core/status.hpp"
#include "common/extrapolation/entities.hpp"

namespace fleetmap::extrapolation {

struct ParsedEntities {
  Entities entities;
  std::vector<std::string> warnings;  // one per skipped entry or ignored key, naming it
};

// Errors (kInvalidArgument) start with `source_name`: not JSON, top level not an object, a known
// class whose value is not an array.
StatusOr<ParsedEntities> ParseEntitiesJson(std::string_view text, std::string_view source_name);

// The JSON text of `entities` (reads back with ParseEntitiesJson to the same entities).
std::string EntitiesToJson(const Entities& entities);

}  // namespace fleetmap::extrapolation
