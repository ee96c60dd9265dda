#include "common/extrapolation/extrapolator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <set>

#include "common/extrapolation/building_outline.hpp"
#include "common/extrapolation/door_space.hpp"
#include "common/extrapolation/kernels.hpp"
#include "common/extrapolation/map_queries.hpp"
#include "common/extrapolation/place_partition.hpp"
#include "common/extrapolation/track_predictor.hpp"

namespace fleetmap::extrapolation {
namespace {

// Predicted grids are cut from windows of the local map's cell lattice (indices may lie outside the
// map), so their cells coincide with the local map's cells.
using LatticeWindow = CellWindow;

// The lattice window covering the disc (map frame), at most `max_side` cells a side.
LatticeWindow WindowAround(const grid::OccupancyGrid& map, const Point2& centre, double radius,
                           int max_side) {
  const Point2 in_grid = map.origin().ToTransform().inverse() * centre;
  const double r = map.resolution();
  const double half = std::min(radius / r, 0.5 * max_side);
  LatticeWindow window;
  window.x0 = static_cast<int>(std::floor(in_grid.x() / r - half));
  window.y0 = static_cast<int>(std::floor(in_grid.y() / r - half));
  window.width = std::max(1, std::min(max_side, static_cast<int>(std::ceil(2.0 * half)) + 1));
  window.height = window.width;
  return window;
}

// An empty predicted sub-map whose grid is `window` of the local lattice, in the frame
// `map_from_submap`.
scene::Submap MakePredictedSubmap(const grid::OccupancyGrid& map, const LatticeWindow& window,
                                  const Pose2& map_from_submap) {
  scene::Submap submap;
  submap.map_from_submap = map_from_submap;
  Transform2 map_from_window = map.origin().ToTransform();
  map_from_window.translate(Vector2(window.x0 * map.resolution(), window.y0 * map.resolution()));
  const Pose2 submap_from_window =
      Pose2::FromTransform(map_from_submap.ToTransform().inverse() * map_from_window);
  submap.navigable = grid::OccupancyGrid(window.width, window.height, map.resolution(),
                                         submap_from_window, grid::kUnknownValue);
  submap.confidence.assign(static_cast<size_t>(submap.navigable.cell_count()), 0.0f);
  return submap;
}

// Coordinates beyond this (metres) are taken as garbage, not as a place: no map is that large, and
// casting them to cell indices would overflow.
constexpr double kMaxCoordinate = 1e6;
// A track point further from the previous one than this speed allows (plus 1 m) is a tracking
// error (m/s).
constexpr double kMaxPersonSpeed = 10.0;

bool Finite(const Point2& p) { return p.allFinite() && p.cwiseAbs().maxCoeff() <= kMaxCoordinate; }

class Extrapolator {
 public:
  Extrapolator(const grid::OccupancyGrid& map, const ExtrapolationOptions& options)
      : map_(map), options_(options) {}

  ExtrapolationResult Run(const scene::Entities& entities) {
    result_.conditionally_free =
        grid::OccupancyGrid(map_.width(), map_.height(), map_.resolution(), map_.origin());
    for (const scene::PersonTrack& person : entities.people) AddPerson(person);
    doors_ = &entities.doors;
    for (const scene::DoorEntity& door : entities.doors) AddDoor(door);
    for (const scene::StairsEntity& stairs : entities.stairs) AddStairs(stairs);
    AddObservedSubmaps();
    for (Separator& separator : separators_) Connect(separator);
    return std::move(result_);
  }

 private:
  // A door (open or closed) or the foot of a flight of stairs: it cuts the observed map into
  // places, and may open onto a predicted sub-map.
  struct Separator {
    std::string id;
    PlaceCut cut;
    Vector2 from_side = Vector2::Zero();  // towards the side it opens from (the robot's)
    std::optional<scene::Submap> predicted;
  };

  // A person who passed the checks: who they are and where they were last seen.
  struct Person {
    std::string id;
    Point2 last_position = Point2::Zero();
  };

  void Warn(const std::string& message) { result_.warnings.push_back(message); }

  // The observed sub-maps, one per place of the local map's free cells plus the people's
  // conditionally free cells (the paper's U'), cut at the separators.
  void AddObservedSubmaps() {
    const size_t n = static_cast<size_t>(map_.cell_count());
    std::vector<uint8_t> free(n, 0);
    for (int y = 0; y < map_.height(); ++y) {
      for (int x = 0; x < map_.width(); ++x) {
        free[static_cast<size_t>(y) * map_.width() + x] =
            map_.StateAt(x, y) == grid::CellState::kFree ||
            result_.conditionally_free.at(x, y) == grid::kFreeValue;
      }
    }
    std::vector<PlaceCut> cuts;
    for (const Separator& s : separators_) cuts.push_back(s.cut);
    const double cell_area = map_.resolution() * map_.resolution();
    const auto min_cells =
        static_cast<int64_t>(std::ceil(options_.min_place_area / cell_area - 1e-9));
    places_ = PartitionPlaces(map_, free, cuts, min_cells);

    // Each place's bounding box (inclusive), grown by one cell for the walls around it.
    struct Box {
      int x0, y0, x1, y1;
    };
    const int count = std::max(1, places_.place_count);
    std::vector<Box> boxes(count, {map_.width(), map_.height(), -1, -1});
    for (int y = 0; y < map_.height(); ++y) {
      for (int x = 0; x < map_.width(); ++x) {
        const int32_t label = places_.Label(x, y);
        if (label < 0) continue;
        Box& b = boxes[label];
        b.x0 = std::min(b.x0, x);
        b.y0 = std::min(b.y0, y);
        b.x1 = std::max(b.x1, x);
        b.y1 = std::max(b.y1, y);
      }
    }
    for (int k = 0; k < count; ++k) {
      LatticeWindow window{0, 0, map_.width(), map_.height()};  // no place: the whole map
      if (places_.place_count > 0) {
        const Box& b = boxes[k];
        window.x0 = std::max(0, b.x0 - 1);
        window.y0 = std::max(0, b.y0 - 1);
        window.width = std::min(map_.width() - 1, b.x1 + 1) - window.x0 + 1;
        window.height = std::min(map_.height() - 1, b.y1 + 1) - window.y0 + 1;
      }
      scene::Submap submap;
      submap.id = static_cast<uint32_t>(k);
      submap.kind = scene::SubmapKind::kObserved;
      submap.place = submap.id;
      Transform2 map_from_window = map_.origin().ToTransform();
      map_from_window.translate(
          Vector2(window.x0 * map_.resolution(), window.y0 * map_.resolution()));
      submap.navigable =
          grid::OccupancyGrid(window.width, window.height, map_.resolution(),
                              Pose2::FromTransform(map_from_window), grid::kUnknownValue);
      for (int y = 0; y < window.height; ++y) {
        for (int x = 0; x < window.width; ++x) {
          const int mx = window.x0 + x, my = window.y0 + y;
          if (places_.place_count > 0 && places_.Label(mx, my) == k) {
            submap.navigable.at(x, y) = grid::kFreeValue;
          } else if (map_.StateAt(mx, my) == grid::CellState::kOccupied) {
            submap.navigable.at(x, y) = grid::kOccupiedValue;
          }
        }
      }
      result_.graph.submaps.push_back(std::move(submap));
    }

    // People: listed in the places their conditionally free cells fall in (or, if they claimed
    // none, the place nearest to where they were last seen).
    std::vector<std::set<int32_t>> places_of_person(people_.size());
    for (size_t i = 0; i < person_of_cell_.size(); ++i) {
      const int32_t label = places_.labels[i];
      if (person_of_cell_[i] >= 0 && label >= 0) places_of_person[person_of_cell_[i]].insert(label);
    }
    for (size_t p = 0; p < people_.size(); ++p) {
      if (places_of_person[p].empty()) {
        places_of_person[p].insert(
            NearestPlace(map_, places_, people_[p].last_position).value_or(0));
      }
      for (int32_t label : places_of_person[p]) ListEntity(label, people_[p].id);
    }
  }

  void ListEntity(int32_t observed_id, const std::string& entity_id) {
    std::vector<std::string>& ids = result_.graph.submaps[observed_id].entity_ids;
    if (std::find(ids.begin(), ids.end(), entity_id) == ids.end()) ids.push_back(entity_id);
  }

  // The edges of one separator: between the observed sub-maps on its two sides (if they differ),
  // and from the observed sub-map it opens from to its predicted sub-map.
  void Connect(Separator& separator) {
    const double depth = std::max(kSideDepth, 4.0 * map_.resolution());
    const std::optional<int32_t> from =
        PlaceBeside(map_, places_, separator.cut.a, separator.cut.b, separator.from_side, depth);
    const std::optional<int32_t> to =
        PlaceBeside(map_, places_, separator.cut.a, separator.cut.b, -separator.from_side, depth);
    if (from) ListEntity(*from, separator.id);
    if (to) ListEntity(*to, separator.id);
    if (from && to && *from != *to) {
      result_.graph.edges.push_back({static_cast<uint32_t>(std::min(*from, *to)),
                                     static_cast<uint32_t>(std::max(*from, *to)), Pose2{},
                                     separator.id});
    }
    if (!separator.predicted) return;
    const Point2 centre = 0.5 * (separator.cut.a + separator.cut.b);
    const int32_t joined = from ? *from : NearestPlace(map_, places_, centre).value_or(0);
    scene::Submap submap = std::move(*separator.predicted);
    const auto id = static_cast<uint32_t>(result_.graph.submaps.size());
    submap.id = id;
    submap.place = id;  // a predicted sub-map is a place of its own
    submap.entity_ids.push_back(separator.id);
    const scene::Submap& observed = result_.graph.submaps[joined];
    result_.graph.edges.push_back(
        {observed.id, id, scene::RelativePose(observed.map_from_submap, submap.map_from_submap),
         separator.id});
    result_.graph.submaps.push_back(std::move(submap));
  }

  void AddPerson(const scene::PersonTrack& person) {
    const std::string name = "person '" + person.id + "'";
    if (person.points.size() < 2) {
      Warn(name + " skipped: a track needs at least two points");
      return;
    }
    for (size_t i = 0; i < person.points.size(); ++i) {
      const scene::TrackPoint& p = person.points[i];
      if (!Finite(p.position) || !std::isfinite(p.stamp) || !std::isfinite(p.heading) ||
          (i > 0 && !(p.stamp > person.points[i - 1].stamp))) {
        Warn(name + " skipped: point " + std::to_string(i) +
             " is not finite (or beyond 1e6 m) or its stamp does not increase");
        return;
      }
      if (i > 0 && (p.position - person.points[i - 1].position).norm() >
                       kMaxPersonSpeed * (p.stamp - person.points[i - 1].stamp) + 1.0) {
        Warn(name + " skipped: point " + std::to_string(i) + " jumps faster than " +
             std::to_string(static_cast<int>(kMaxPersonSpeed)) + " m/s (a tracking error)");
        return;
      }
    }
    int side = person.dominant_side;
    if (side != -1 && side != 1) {
      const std::optional<int> inferred =
          InferDominantSide(map_, person, options_.dominant_side_search);
      side = inferred.value_or(1);
      if (!inferred) Warn(name + ": no obstacle beside the track, dominant side taken as right");
    }
    TrackPredictorOptions sweep_options;
    sweep_options.horizon = options_.track_horizon;
    sweep_options.sample_spacing = options_.track_sample_spacing;
    std::vector<SweptPose> poses = SweepTrack(person, sweep_options);
    // A predicted walk stops at the first known obstacle.
    for (size_t i = 1; i < poses.size(); ++i) {
      if (poses[i].predicted && !LineOfSight(map_, poses[i - 1].position, poses[i].position)) {
        poses.resize(i);
        break;
      }
    }
    const SkewNormalKernel kernel(
        options_.person_sigma_forward, options_.person_sigma_side,
        Vector2(options_.person_skew_forward, side * options_.person_skew_side));
    const double radius = kernel.SupportRadius(options_.p_th);
    grid::OccupancyGrid& out = result_.conditionally_free;
    const auto person_index = static_cast<int32_t>(people_.size());
    int64_t claimed = 0;
    for (const SweptPose& pose : poses) {
      const LatticeWindow w = WindowAround(map_, pose.position, radius, 4096);
      const Eigen::Rotation2Dd person_from_map(-pose.heading);
      for (int y = std::max(0, w.y0); y < std::min(map_.height(), w.y0 + w.height); ++y) {
        for (int x = std::max(0, w.x0); x < std::min(map_.width(), w.x0 + w.width); ++x) {
          if (out.at(x, y) == grid::kFreeValue) continue;
          if (map_.StateAt(x, y) == grid::CellState::kOccupied) continue;
          const Point2 c = map_.CellCenter(x, y);
          if (kernel.Normalized(person_from_map * (c - pose.position)) <= options_.p_th) continue;
          if (!LineOfSight(map_, pose.position, c)) continue;
          out.at(x, y) = grid::kFreeValue;
          if (person_of_cell_.empty()) {
            person_of_cell_.assign(static_cast<size_t>(map_.cell_count()), -1);
          }
          person_of_cell_[static_cast<size_t>(y) * map_.width() + x] = person_index;
          ++claimed;
        }
      }
    }
    people_.push_back({person.id, person.points.back().position});
    if (claimed == 0) Warn(name + ": no cell of the local map could be claimed free");
  }

  void AddDoor(const scene::DoorEntity& door) {
    const std::string name = "door '" + door.id + "'";
    const double w = door.width();
    if (!Finite(door.hinge) || !Finite(door.latch) || !door.opening_direction.allFinite()) {
      Warn(name + " skipped: a coordinate is not finite (or beyond 1e6 m)");
      return;
    }
    if (!(w >= 0.2)) {
      Warn(name + " skipped: width " + std::to_string(w) + " m (hinge and latch coincide)");
      return;
    }
    const Vector2 along = (door.latch - door.hinge) / w;
    // Open or closed, a door separates two places.
    Separator& separator = separators_.emplace_back();
    separator.id = door.id;
    separator.cut = {door.hinge, door.latch};
    separator.from_side = Vector2(along.y(), -along.x());
    Vector2 opening = door.opening_direction - door.opening_direction.dot(along) * along;
    if (opening.norm() >= 1e-6) separator.from_side = -opening.normalized();
    // An open doorway is seen through: the space behind it is observed, not predicted.
    if (door.open) return;
    opening = door.opening_direction;
    if (opening.norm() < 1e-6) {
      const std::optional<Vector2> inferred = InferOpeningDirection(map_, door);
      if (!inferred) {
        Warn(name +
             " predicts nothing: no opening direction given and the map does not tell which "
             "side is unseen");
        return;
      }
      opening = *inferred;
    }
    opening -= opening.dot(along) * along;
    if (opening.norm() < 1e-6) {
      Warn(name + " predicts nothing: its opening direction runs along the door");
      return;
    }
    opening.normalize();
    separator.from_side = -opening;

    const Point2 centre = door.center();
    const Point2 origin = centre + options_.door_submap_distance * opening;
    const double yaw = std::atan2(opening.y(), opening.x()) - 0.5 * std::numbers::pi;
    const Pose2 map_from_submap{origin.x(), origin.y(), NormalizeAngle(yaw)};
    // Kernel frame: origin at the doorway's centre, x along the door line, y into the room. The
    // kernel is symmetric along the door, so which jamb is the hinge does not matter: where the
    // room lies beside the doorway is the map's to say (DoorSpace), not the hinge's.
    const Vector2 kx(opening.y(), -opening.x());
    const SkewNormalKernel kernel(options_.door_sigma_along_per_width * w,
                                  options_.door_sigma_depth_per_width * w,
                                  Vector2(0.0, options_.door_skew_per_width * w));
    const double reach =
        std::min(options_.door_max_range, kernel.SupportRadius(options_.p_th) + 0.5 * w);
    const LatticeWindow window = WindowAround(map_, centre, reach, options_.max_submap_cells_side);
    scene::Submap submap = MakePredictedSubmap(map_, window, map_from_submap);
    submap.kind = scene::SubmapKind::kPredictedDoor;

    DoorSpaceOptions space_options;
    space_options.unseen_wall_thickness = options_.door_unseen_wall_thickness;
    space_options.min_passage_width = options_.door_min_passage_width;
    space_options.min_continued_wall = options_.door_min_continued_wall;
    space_options.continuation_gap = options_.door_continuation_gap;
    space_options.wall_clearance = options_.door_wall_clearance;
    const DoorSpace space(map_, door, opening, window, space_options);
    std::vector<uint8_t> candidate = space.allowed();
    for (int y = 0; y < window.height; ++y) {
      for (int x = 0; x < window.width; ++x) {
        const Point2 c = map_.CellCenter(window.x0 + x, window.y0 + y);
        const Vector2 d = c - centre;
        const double conf = kernel.Normalized(Vector2(kx.dot(d), opening.dot(d)));
        const size_t i = static_cast<size_t>(y) * window.width + x;
        submap.confidence[i] = static_cast<float>(conf);
        candidate[i] = candidate[i] && conf > options_.p_th && d.norm() <= options_.door_max_range;
      }
    }
    // What a person could walk to is judged before the building's bounds cut the room: a bound
    // cutting across the room makes new corners, and the walkability opening would round them
    // off, taking cells of the room that neither rule excludes.
    std::vector<uint8_t> reached = space.ReachableFromDoorway(candidate);
    if (ApplyBuildingBounds(door, opening, centre, kx, window, &reached)) {
      reached = space.ConnectedToDoorway(reached);
    }
    int64_t free = 0;
    for (int y = 0; y < window.height; ++y) {
      for (int x = 0; x < window.width; ++x) {
        if (reached[static_cast<size_t>(y) * window.width + x]) {
          submap.navigable.at(x, y) = grid::kFreeValue;
          ++free;
        }
      }
    }
    if (free == 0) Warn(name + ": no free space predicted behind it (blocked or below p_th)");
    separator.predicted = std::move(submap);
  }

  void AddStairs(const scene::StairsEntity& stairs) {
    const std::string name = "stairs '" + stairs.id + "'";
    if (!Finite(stairs.position) || !stairs.ascending.allFinite() ||
        !std::isfinite(stairs.step_width) || !std::isfinite(stairs.next_floor_height) ||
        !std::isfinite(stairs.run_length) || stairs.run_length > kMaxCoordinate ||
        stairs.step_width > kMaxCoordinate) {
      Warn(name + " skipped: a value is not finite (or beyond 1e6 m)");
      return;
    }
    if (stairs.ascending.norm() < 1e-6 || !(stairs.step_width > 0.0) ||
        !(stairs.next_floor_height > 0.0) || stairs.run_length < 0.0) {
      Warn(name + " skipped: zero ascending direction, or step width / floor height <= 0");
      return;
    }
    const Vector2 up = stairs.ascending.normalized();
    // The foot of the flight separates this floor's place from the stairs.
    const Vector2 across(-up.y(), up.x());
    Separator& separator = separators_.emplace_back();
    separator.id = stairs.id;
    separator.cut = {stairs.position - 0.5 * stairs.step_width * across,
                     stairs.position + 0.5 * stairs.step_width * across};
    separator.from_side = -up;
    const double run = stairs.run_length > 0.0
                           ? stairs.run_length
                           : stairs.next_floor_height / std::tan(options_.stairs_default_pitch);
    const Point2 top = stairs.position + run * up;
    const Pose2 map_from_submap{top.x(), top.y(), std::atan2(up.y(), up.x())};
    const double sigma = options_.stairs_sigma_per_width * stairs.step_width;
    const double radius = sigma * std::sqrt(-2.0 * std::log(options_.p_th));
    const LatticeWindow window = WindowAround(map_, top, radius, options_.max_submap_cells_side);
    scene::Submap submap = MakePredictedSubmap(map_, window, map_from_submap);
    submap.kind = scene::SubmapKind::kPredictedStairs;
    submap.elevation = stairs.next_floor_height;
    // The floor above is not this map's: only the half-plane beyond the top edge is predicted
    // (behind it is the stairwell).
    for (int y = 0; y < window.height; ++y) {
      for (int x = 0; x < window.width; ++x) {
        const Vector2 d = map_.CellCenter(window.x0 + x, window.y0 + y) - top;
        const double conf = NormalizedGaussian(d, sigma);
        submap.confidence[static_cast<size_t>(y) * window.width + x] = static_cast<float>(conf);
        if (conf > options_.p_th && d.dot(up) > options_.stairs_edge_clearance) {
          submap.navigable.at(x, y) = grid::kFreeValue;
        }
      }
    }
    separator.predicted = std::move(submap);
  }

  // How far from a separator its sides are looked at (metres; at least four cells).
  static constexpr double kSideDepth = 0.3;

  // Clears the cells of `mask` (window-sized) outside the building's outline or past the next
  // closed door in the same wall (the options say which rules apply); false when neither does.
  bool ApplyBuildingBounds(const scene::DoorEntity& door, const Vector2& opening,
                           const Point2& centre, const Vector2& kx, const LatticeWindow& window,
                           std::vector<uint8_t>* mask) {
    if (options_.door_building_outline) {
      if (!outline_) {
        BuildingOutlineOptions outline_options;
        outline_options.min_outer_wall = options_.door_min_outer_wall;
        outline_options.max_face_gap = options_.door_min_passage_width;
        outline_options.continuation_gap = options_.door_continuation_gap;
        outline_.emplace(map_, outline_options);
      }
      const std::vector<uint8_t> in_building = outline_->AllowedFor(door, opening);
      for (int y = 0; y < window.height; ++y) {
        for (int x = 0; x < window.width; ++x) {
          const int mx = window.x0 + x, my = window.y0 + y;
          // Off the map: no outline known there, the other rules alone decide.
          if (!map_.Contains(mx, my)) continue;
          uint8_t& c = (*mask)[static_cast<size_t>(y) * window.width + x];
          c = c && in_building[static_cast<size_t>(my) * map_.width() + mx];
        }
      }
    }
    if (options_.door_split_between_doors) {
      // Another closed door in the same wall, opening to the same side, leads to another room:
      // the room behind this one ends before the other doorway (NeighbourDoorLimits).
      // A cell any part of which is inside the limits is kept (half a cell's reach).
      const double half = 0.5 * map_.resolution();
      const std::vector<std::pair<double, double>> limits = NeighbourDoorLimits(door, opening);
      for (int y = 0; y < window.height; ++y) {
        for (int x = 0; x < window.width; ++x) {
          const double s = kx.dot(map_.CellCenter(window.x0 + x, window.y0 + y) - centre);
          uint8_t& c = (*mask)[static_cast<size_t>(y) * window.width + x];
          for (const auto& [lo, hi] : limits) c = c && s > lo - half && s < hi + half;
        }
      }
    }
    return options_.door_building_outline || options_.door_split_between_doors;
  }

  // The lateral limits (along the door line from its centre, x as in the kernel frame: opening
  // turned clockwise) that the other closed doors in the same wall set: (-inf, l) for one of
  // width w at lateral offset s > 0, with l = s - w / 2 - door_next_room_clearance (short of its
  // near jamb), and (-l, inf) for one at s < 0. Same wall: parallel within 10 degrees,
  // centres within 0.5 m across the wall, opening to the same side, doorways apart.
  std::vector<std::pair<double, double>> NeighbourDoorLimits(const scene::DoorEntity& door,
                                                             const Vector2& opening) const {
    std::vector<std::pair<double, double>> limits;
    const double inf = std::numeric_limits<double>::infinity();
    const Vector2 kx(opening.y(), -opening.x());
    const Point2 centre = door.center();
    for (const scene::DoorEntity& other : *doors_) {
      if (other.id == door.id || other.open || !Finite(other.hinge) || !Finite(other.latch) ||
          !other.opening_direction.allFinite() || !(other.width() >= 0.2)) {
        continue;
      }
      const Vector2 along = (other.latch - other.hinge) / other.width();
      const Vector2 d = other.center() - centre;
      if (std::abs(along.dot(kx)) < std::cos(10.0 * std::numbers::pi / 180.0) ||
          std::abs(d.dot(opening)) > 0.5 || !(other.opening_direction.dot(opening) > 0.0)) {
        continue;
      }
      const double s = d.dot(kx);
      if (std::abs(s) <= 0.5 * (door.width() + other.width())) continue;
      const double last = std::abs(s) - 0.5 * other.width() - options_.door_next_room_clearance;
      limits.emplace_back(s > 0.0 ? -inf : -last, s > 0.0 ? last : inf);
    }
    return limits;
  }

  const grid::OccupancyGrid& map_;
  const ExtrapolationOptions& options_;
  // Made on the first closed door's prediction (the whole map is looked at once per call).
  std::optional<BuildingOutline> outline_;
  const std::vector<scene::DoorEntity>* doors_ = nullptr;  // every door of the call
  ExtrapolationResult result_;
  std::vector<Person> people_;
  // The person who claimed each conditionally free cell (-1: none; empty until one does).
  std::vector<int32_t> person_of_cell_;
  std::vector<Separator> separators_;  // in entity order: doors, then stairs
  PlacePartition places_;
};

}  // namespace

Status ExtrapolationOptions::Validate() const {
  const ExtrapolationOptions& o = *this;
  if (!(o.p_th > 0.0 && o.p_th < 1.0)) {
    return InvalidArgumentError("p_th " + std::to_string(o.p_th) + " must be in (0, 1)");
  }
  const std::pair<const char*, double> positive[] = {
      {"stairs_sigma_per_width", o.stairs_sigma_per_width},
      {"stairs_default_pitch", o.stairs_default_pitch},
      {"door_sigma_along_per_width", o.door_sigma_along_per_width},
      {"door_sigma_depth_per_width", o.door_sigma_depth_per_width},
      {"door_max_range", o.door_max_range},
      {"door_min_passage_width", o.door_min_passage_width},
      {"door_min_continued_wall", o.door_min_continued_wall},
      {"person_sigma_forward", o.person_sigma_forward},
      {"person_sigma_side", o.person_sigma_side},
      {"track_sample_spacing", o.track_sample_spacing},
      {"dominant_side_search", o.dominant_side_search},
  };
  for (const auto& [name, value] : positive) {
    if (!(value > 0.0) || !std::isfinite(value)) {
      return InvalidArgumentError(std::string(name) + " must be a finite number > 0");
    }
  }
  const std::pair<const char*, double> non_negative[] = {
      {"door_skew_per_width", o.door_skew_per_width},
      {"door_submap_distance", o.door_submap_distance},
      {"door_wall_clearance", o.door_wall_clearance},
      {"door_unseen_wall_thickness", o.door_unseen_wall_thickness},
      {"door_next_room_clearance", o.door_next_room_clearance},
      {"door_continuation_gap", o.door_continuation_gap},
      {"door_min_outer_wall", o.door_min_outer_wall},
      {"stairs_edge_clearance", o.stairs_edge_clearance},
      {"person_skew_forward", o.person_skew_forward},
      {"person_skew_side", o.person_skew_side},
      {"track_horizon", o.track_horizon},
      {"min_place_area", o.min_place_area},
  };
  for (const auto& [name, value] : non_negative) {
    if (!(value >= 0.0) || !std::isfinite(value)) {
      return InvalidArgumentError(std::string(name) + " must be a finite number >= 0");
    }
  }
  if (!(o.stairs_default_pitch < 0.5 * std::numbers::pi)) {
    return InvalidArgumentError("stairs_default_pitch must be below pi / 2");
  }
  if (o.max_submap_cells_side < 1) {
    return InvalidArgumentError("max_submap_cells_side must be >= 1");
  }
  return Status::Ok();
}

StatusOr<ExtrapolationResult> Extrapolate(const grid::OccupancyGrid& local_map,
                                          const scene::Entities& entities,
                                          const ExtrapolationOptions& options) {
  FLEETMAP_RETURN_IF_ERROR(options.Validate());
  if (local_map.empty()) return InvalidArgumentError("the local map is empty");
  return Extrapolator(local_map, options).Run(entities);
}

void ExtrapolationOptions::Describe(OptionsPrinter& out) const {
  out.Add("p_th", p_th);
  out.Add("stairs_sigma_per_width", stairs_sigma_per_width);
  out.Add("stairs_edge_clearance", stairs_edge_clearance);
  out.Add("stairs_default_pitch", stairs_default_pitch);
  out.Add("door_sigma_along_per_width", door_sigma_along_per_width);
  out.Add("door_sigma_depth_per_width", door_sigma_depth_per_width);
  out.Add("door_skew_per_width", door_skew_per_width);
  out.Add("door_wall_clearance", door_wall_clearance);
  out.Add("door_submap_distance", door_submap_distance);
  out.Add("door_max_range", door_max_range);
  out.Add("door_unseen_wall_thickness", door_unseen_wall_thickness);
  out.Add("door_min_passage_width", door_min_passage_width);
  out.Add("door_min_continued_wall", door_min_continued_wall);
  out.Add("door_continuation_gap", door_continuation_gap);
  out.Add("door_building_outline", door_building_outline);
  out.Add("door_min_outer_wall", door_min_outer_wall);
  out.Add("door_split_between_doors", door_split_between_doors);
  out.Add("door_next_room_clearance", door_next_room_clearance);
  out.Add("person_sigma_forward", person_sigma_forward);
  out.Add("person_sigma_side", person_sigma_side);
  out.Add("person_skew_forward", person_skew_forward);
  out.Add("person_skew_side", person_skew_side);
  out.Add("track_horizon", track_horizon);
  out.Add("track_sample_spacing", track_sample_spacing);
  out.Add("dominant_side_search", dominant_side_search);
  out.Add("min_place_area", min_place_area);
  out.Add("max_submap_cells_side", max_submap_cells_side);
}

}  // namespace fleetmap::extrapolation
