#include "common/extrapolation/entities_json.hpp"

#include <cmath>
#include <cstdio>
#include <optional>
#include <set>

#include <nlohmann/json.hpp>

namespace fleetmap::extrapolation {
namespace {

using nlohmann::json;

// Door widths outside this range are not doors (metres).
constexpr double kMinDoorWidth = 0.2;
constexpr double kMaxDoorWidth = 4.0;

// Reads fields of one entry; the first problem is kept in `error` and later reads are no-ops.
class EntryReader {
 public:
  explicit EntryReader(const json& entry) : entry_(entry) {}

  const std::optional<std::string>& error() const { return error_; }
  void Fail(std::string message) {
    if (!error_) error_ = std::move(message);
  }

  double Number(const char* key, std::optional<double> fallback = std::nullopt) {
    if (error_) return 0.0;
    const auto it = entry_.find(key);
    if (it == entry_.end()) {
      if (fallback) return *fallback;
      Fail(std::string("missing '") + key + "'");
      return 0.0;
    }
    if (!it->is_number()) {
      Fail(std::string("'") + key + "' is not a number");
      return 0.0;
    }
    const double value = it->get<double>();
    if (!std::isfinite(value)) Fail(std::string("'") + key + "' is not finite");
    return value;
  }

  Point2 Vector(const char* key, std::optional<Point2> fallback = std::nullopt) {
    if (error_) return Point2::Zero();
    const auto it = entry_.find(key);
    if (it == entry_.end()) {
      if (fallback) return *fallback;
      Fail(std::string("missing '") + key + "'");
      return Point2::Zero();
    }
    if (!it->is_array() || it->size() != 2 || !(*it)[0].is_number() || !(*it)[1].is_number()) {
      Fail(std::string("'") + key + "' is not an array of two numbers");
      return Point2::Zero();
    }
    const Point2 value((*it)[0].get<double>(), (*it)[1].get<double>());
    if (!value.allFinite()) Fail(std::string("'") + key + "' is not finite");
    return value;
  }

  bool Bool(const char* key, bool fallback) {
    if (error_) return fallback;
    const auto it = entry_.find(key);
    if (it == entry_.end()) return fallback;
    if (!it->is_boolean()) {
      Fail(std::string("'") + key + "' is not true or false");
      return fallback;
    }
    return it->get<bool>();
  }

 private:
  const json& entry_;
  std::optional<std::string> error_;
};

json ToJson(const Point2& p) { return json::array({p.x(), p.y()}); }

std::string Metres(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.3g m", value);
  return buffer;
}

std::optional<scene::DoorEntity> ParseDoor(const json& entry, EntryReader& reader,
                                           std::vector<std::string>* notes) {
  scene::DoorEntity door;
  door.hinge = reader.Vector("hinge");
  door.latch = reader.Vector("latch");
  // A zero opening direction asks the extrapolator to orient the door from the map.
  door.opening_direction = reader.Vector("opening_direction", Point2::Zero());
  door.open = reader.Bool("open", false);
  if (reader.error()) return std::nullopt;
  const double width = door.width();
  if (!(width >= kMinDoorWidth && width <= kMaxDoorWidth)) {
    reader.Fail("width " + Metres(width) + " is not a door's (hinge to latch must be " +
                Metres(kMinDoorWidth) + " to " + Metres(kMaxDoorWidth) + ")");
    return std::nullopt;
  }
  const double norm = door.opening_direction.norm();
  if (norm > 0.0) {
    // Keep only the part normal to the door line: the door opens across it.
    const Vector2 along = (door.latch - door.hinge) / width;
    Vector2 normal = door.opening_direction / norm;
    normal -= normal.dot(along) * along;
    if (normal.norm() < 0.1) {
      reader.Fail("'opening_direction' runs along the door line");
      return std::nullopt;
    }
    door.opening_direction = normal.normalized();
  } else if (entry.contains("opening_direction")) {
    notes->push_back("'opening_direction' is zero: inferred from the map");
  }
  return door;
}

std::optional<scene::StairsEntity> ParseStairs(EntryReader& reader) {
  scene::StairsEntity stairs;
  stairs.position = reader.Vector("position");
  stairs.ascending = reader.Vector("ascending");
  stairs.step_width = reader.Number("step_width");
  stairs.next_floor_height = reader.Number("next_floor_height", 3.0);
  stairs.run_length = reader.Number("run_length", 0.0);
  if (reader.error()) return std::nullopt;
  if (stairs.ascending.norm() < 1e-6) {
    reader.Fail("'ascending' is zero");
  } else if (!(stairs.step_width > 0.0)) {
    reader.Fail("'step_width' must be > 0");
  } else if (!(stairs.next_floor_height > 0.0)) {
    reader.Fail("'next_floor_height' must be > 0");
  } else if (stairs.run_length < 0.0) {
    reader.Fail("'run_length' must be >= 0");
  }
  if (reader.error()) return std::nullopt;
  stairs.ascending.normalize();
  return stairs;
}

std::optional<scene::PersonTrack> ParsePerson(const json& entry, EntryReader& reader,
                                              std::vector<std::string>* notes) {
  scene::PersonTrack track;
  track.dominant_side = static_cast<int>(reader.Number("dominant_side", 0.0));
  track.left_view = reader.Bool("left_view", false);
  track.entered_view = reader.Bool("entered_view", false);
  if (reader.error()) return std::nullopt;
  if (track.dominant_side < -1 || track.dominant_side > 1) {
    notes->push_back("'dominant_side' must be -1, 0 or +1: inferred from the map instead");
    track.dominant_side = 0;
  }
  const auto it = entry.find("track");
  if (it == entry.end() || !it->is_array()) {
    reader.Fail(it == entry.end() ? "missing 'track'" : "'track' is not an array");
    return std::nullopt;
  }
  int skipped = 0;
  for (size_t i = 0; i < it->size(); ++i) {
    const json& point = (*it)[i];
    if (!point.is_object()) {
      ++skipped;
      continue;
    }
    EntryReader point_reader(point);
    scene::TrackPoint p;
    p.stamp = point_reader.Number("stamp");
    p.position = point_reader.Vector("position");
    p.heading = point_reader.Number("heading", 0.0);
    if (point_reader.error()) {
      notes->push_back("track point " + std::to_string(i) + " skipped: " + *point_reader.error());
      continue;
    }
    if (!track.points.empty() && !(p.stamp > track.points.back().stamp)) {
      notes->push_back("track point " + std::to_string(i) +
                       " skipped: its stamp does not increase");
      continue;
    }
    track.points.push_back(p);
  }
  if (skipped > 0) {
    notes->push_back(std::to_string(skipped) + " track point(s) that are not objects skipped");
  }
  if (track.points.size() < 2) {
    reader.Fail("a track needs at least two usable points, it has " +
                std::to_string(track.points.size()));
    return std::nullopt;
  }
  return track;
}

}  // namespace

StatusOr<ParsedEntities> ParseEntitiesJson(std::string_view text, std::string_view source_name) {
  const std::string source(source_name);
  json root;
  try {
    root = json::parse(text.begin(), text.end());
  } catch (const json::exception& e) {
    return InvalidArgumentError(source + ": not valid JSON: " + e.what());
  }
  if (!root.is_object()) return InvalidArgumentError(source + ": the top level is not an object");
  const auto list = root.find("entities");
  if (list == root.end() || !list->is_array()) {
    return InvalidArgumentError(source + ": no \"entities\" array at the top level");
  }
  ParsedEntities parsed;
  for (const auto& [key, value] : root.items()) {
    if (key != "entities" && key != "frame") {
      parsed.warnings.push_back(source + ": unknown key '" + key + "' ignored");
    }
  }
  std::set<std::string> ids;
  for (size_t i = 0; i < list->size(); ++i) {
    const json& entry = (*list)[i];
    std::string name = source + ": entity #" + std::to_string(i);
    if (!entry.is_object()) {
      parsed.warnings.push_back(name + " skipped: not an object");
      continue;
    }
    const auto id_it = entry.find("id");
    const auto class_it = entry.find("class");
    const std::string cls =
        class_it != entry.end() && class_it->is_string() ? class_it->get<std::string>() : "";
    if (id_it != entry.end() && id_it->is_string() && !id_it->get<std::string>().empty()) {
      name += " ('" + id_it->get<std::string>() + "')";
    } else {
      parsed.warnings.push_back(name + " skipped: missing 'id' (a non-empty string)");
      continue;
    }
    const std::string id = id_it->get<std::string>();
    if (cls.empty()) {
      parsed.warnings.push_back(name + " skipped: missing 'class'");
      continue;
    }
    if (ids.count(id) > 0) {
      parsed.warnings.push_back(name + " skipped: duplicate id");
      continue;
    }
    EntryReader reader(entry);
    std::vector<std::string> notes;
    bool known = true;
    if (cls == "door") {
      if (std::optional<scene::DoorEntity> door = ParseDoor(entry, reader, &notes)) {
        door->id = id;
        parsed.entities.doors.push_back(*door);
      }
    } else if (cls == "stairs") {
      if (std::optional<scene::StairsEntity> stairs = ParseStairs(reader)) {
        stairs->id = id;
        parsed.entities.stairs.push_back(*stairs);
      }
    } else if (cls == "person") {
      if (std::optional<scene::PersonTrack> track = ParsePerson(entry, reader, &notes)) {
        track->id = id;
        parsed.entities.people.push_back(std::move(*track));
      }
    } else {
      known = false;
      parsed.warnings.push_back(name + " skipped: unknown class '" + cls +
                                "' (use door, stairs or person)");
    }
    for (const std::string& note : notes) parsed.warnings.push_back(name + ": " + note);
    if (!known) continue;
    if (reader.error()) {
      parsed.warnings.push_back(name + " (" + cls + ") skipped: " + *reader.error());
      continue;
    }
    ids.insert(id);
  }
  return parsed;
}

std::string EntitiesToJson(const scene::Entities& entities) {
  json list = json::array();
  for (const scene::DoorEntity& door : entities.doors) {
    list.push_back({{"class", "door"},
                    {"id", door.id},
                    {"hinge", ToJson(door.hinge)},
                    {"latch", ToJson(door.latch)},
                    {"opening_direction", ToJson(door.opening_direction)},
                    {"open", door.open}});
  }
  for (const scene::StairsEntity& stairs : entities.stairs) {
    list.push_back({{"class", "stairs"},
                    {"id", stairs.id},
                    {"position", ToJson(stairs.position)},
                    {"ascending", ToJson(stairs.ascending)},
                    {"step_width", stairs.step_width},
                    {"next_floor_height", stairs.next_floor_height},
                    {"run_length", stairs.run_length}});
  }
  for (const scene::PersonTrack& person : entities.people) {
    json track = json::array();
    for (const scene::TrackPoint& p : person.points) {
      track.push_back(
          {{"stamp", p.stamp}, {"position", ToJson(p.position)}, {"heading", p.heading}});
    }
    list.push_back({{"class", "person"},
                    {"id", person.id},
                    {"dominant_side", person.dominant_side},
                    {"left_view", person.left_view},
                    {"entered_view", person.entered_view},
                    {"track", track}});
  }
  return json{{"frame", "map"}, {"entities", list}}.dump(2) + "\n";
}

}  // namespace fleetmap::extrapolation
