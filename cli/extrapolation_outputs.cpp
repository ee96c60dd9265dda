#include "cli/extrapolation_outputs.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "common/gis/filled_area.hpp"
#include "common/gis/geojson_geometry.hpp"
#include "common/grid/image_file.hpp"

namespace fleetmap::cli {
namespace {

using scene::Submap;
using scene::SubmapKind;

const char* ClassOf(SubmapKind kind) {
  switch (kind) {
    case SubmapKind::kPredictedStairs:
      return "static";
    case SubmapKind::kPredictedDoor:
      return "quasi-static";
    case SubmapKind::kObserved:
      return "dynamic";
  }
  return "unknown";
}

// The free cells of `grid` as valid simple features (common/gis/filled_area.hpp), one FilledArea
// per connected region: cv::findContours traces each region's outer outline and its holes through
// the centres of its boundary cells (map frame by `map_from_grid`), and a region one cell wide
// becomes a line, a lone cell a point.
StatusOr<std::vector<gis::FilledArea>> FreeAreas(const grid::OccupancyGrid& grid,
                                                 const Transform2& map_from_grid) {
  cv::Mat mask(grid.height(), grid.width(), CV_8UC1, cv::Scalar(0));
  for (int y = 0; y < grid.height(); ++y) {
    for (int x = 0; x < grid.width(); ++x) {
      if (grid.StateAt(x, y) == grid::CellState::kFree) mask.at<uint8_t>(y, x) = 255;
    }
  }
  std::vector<std::vector<cv::Point>> contours;
  std::vector<cv::Vec4i> hierarchy;
  cv::findContours(mask, contours, hierarchy, cv::RETR_CCOMP, cv::CHAIN_APPROX_SIMPLE);
  auto ring = [&](const std::vector<cv::Point>& contour) {
    std::vector<Point2> points;
    for (const cv::Point& p : contour) points.push_back(map_from_grid * grid.CellCenter(p.x, p.y));
    return points;
  };
  std::vector<gis::FilledArea> areas;
  for (size_t i = 0; i < contours.size(); ++i) {
    if (hierarchy[i][3] >= 0) continue;  // a hole: added with its outer ring
    std::vector<std::vector<Point2>> rings = {ring(contours[i])};
    for (int child = hierarchy[i][2]; child >= 0; child = hierarchy[child][0]) {
      rings.push_back(ring(contours[child]));
    }
    FLEETMAP_ASSIGN_OR_RETURN(gis::FilledArea area, gis::FilledAreaOfRings(rings));
    areas.push_back(std::move(area));
  }
  return areas;
}

}  // namespace

StatusOr<nlohmann::json> PredictedFreeGeoJson(const extrapolation::ExtrapolationResult& result,
                                              double p_th) {
  nlohmann::json features = nlohmann::json::array();
  auto add = [&](const StatusOr<std::vector<gis::FilledArea>>& areas,
                 nlohmann::json properties) -> Status {
    if (!areas.ok()) return areas.status();
    properties["p_th"] = p_th;
    for (const gis::FilledArea& area : *areas) {
      for (nlohmann::json& geometry : gis::GeoJsonGeometries(area)) {
        features.push_back(
            {{"type", "Feature"}, {"geometry", std::move(geometry)}, {"properties", properties}});
      }
    }
    return Status::Ok();
  };
  for (const Submap& s : result.graph.submaps) {
    if (s.kind != SubmapKind::kObserved) {
      FLEETMAP_RETURN_IF_ERROR(add(FreeAreas(s.navigable, s.map_from_submap.ToTransform()),
                                   {{"submap", s.id},
                                    {"kind", scene::SubmapKindName(s.kind)},
                                    {"class", ClassOf(s.kind)},
                                    {"entities", s.entity_ids},
                                    {"elevation", s.elevation}}));
      continue;
    }
    // The people's conditionally free cells in this observed sub-map's place.
    grid::OccupancyGrid people = s.navigable;
    const Transform2 map_from_submap = s.map_from_submap.ToTransform();
    bool any = false;
    for (int y = 0; y < people.height(); ++y) {
      for (int x = 0; x < people.width(); ++x) {
        const auto cell =
            result.conditionally_free.CellAt(map_from_submap * people.CellCenter(x, y));
        const bool free =
            people.StateAt(x, y) == grid::CellState::kFree && cell &&
            result.conditionally_free.StateAt(cell->x, cell->y) == grid::CellState::kFree;
        people.at(x, y) = free ? grid::kFreeValue : grid::kUnknownValue;
        any |= free;
      }
    }
    if (!any) continue;
    FLEETMAP_RETURN_IF_ERROR(
        add(FreeAreas(people, map_from_submap), {{"submap", s.id},
                                                 {"kind", "conditionally_free"},
                                                 {"class", "dynamic"},
                                                 {"entities", s.entity_ids},
                                                 {"elevation", 0.0}}));
  }
  return nlohmann::json{
      {"type", "FeatureCollection"}, {"crs", gis::GeoJsonCrs()}, {"features", features}};
}

Status WriteOverlayPng(const extrapolation::ExtrapolationResult& result,
                       const extrapolation::FloorGrids& floor, const scene::Entities& entities,
                       const std::string& path) {
  const grid::OccupancyGrid& g = floor.extrapolated;
  const int scale = std::clamp(1600 / std::max(1, std::max(g.width(), g.height())), 1, 4);
  cv::Mat image(g.height() * scale, g.width() * scale, CV_8UC3);
  const Transform2 grid_from_map = g.origin().ToTransform().inverse();
  // Map point -> pixel (row 0 at the top: north up).
  auto pixel = [&](const Point2& p) {
    const Point2 q = grid_from_map * p / g.resolution();
    return cv::Point(static_cast<int>(std::lround(q.x() * scale)),
                     static_cast<int>(std::lround((g.height() - q.y()) * scale)));
  };
  const cv::Vec3b kOccupied(0, 0, 0), kFree(255, 255, 255), kUnknown(160, 160, 160);
  const cv::Vec3b kDoorFree(120, 220, 120), kPeople(60, 170, 255);
  for (int y = 0; y < g.height(); ++y) {
    for (int x = 0; x < g.width(); ++x) {
      cv::Vec3b colour = kUnknown;
      switch (g.StateAt(x, y)) {
        case grid::CellState::kOccupied:
          colour = kOccupied;
          break;
        case grid::CellState::kFree:
          colour = kFree;
          break;
        case grid::CellState::kUnknown:
          break;
      }
      if (floor.predicted_free.StateAt(x, y) == grid::CellState::kFree) {
        const Point2 c = g.CellCenter(x, y);
        const auto local = result.conditionally_free.CellAt(c);
        const bool person = local && result.conditionally_free.StateAt(local->x, local->y) ==
                                         grid::CellState::kFree;
        colour = person ? kPeople : kDoorFree;
      }
      const int row = (g.height() - 1 - y) * scale;
      for (int dy = 0; dy < scale; ++dy) {
        for (int dx = 0; dx < scale; ++dx) image.at<cv::Vec3b>(row + dy, x * scale + dx) = colour;
      }
    }
  }
  for (const Submap& s : result.graph.submaps) {
    if (s.kind != SubmapKind::kPredictedStairs) continue;
    const grid::OccupancyGrid up = extrapolation::SubmapGridInMapFrame(s);
    for (int y = 0; y < up.height(); ++y) {
      for (int x = 0; x < up.width(); ++x) {
        if (up.StateAt(x, y) != grid::CellState::kFree) continue;
        const bool edge = x == 0 || y == 0 || x + 1 == up.width() || y + 1 == up.height() ||
                          up.StateAt(x - 1, y) != grid::CellState::kFree ||
                          up.StateAt(x + 1, y) != grid::CellState::kFree ||
                          up.StateAt(x, y - 1) != grid::CellState::kFree ||
                          up.StateAt(x, y + 1) != grid::CellState::kFree;
        if (edge) cv::circle(image, pixel(up.CellCenter(x, y)), scale, cv::Scalar(40, 40, 230), -1);
      }
    }
  }
  for (const scene::PersonTrack& person : entities.people) {
    for (size_t i = 1; i < person.points.size(); ++i) {
      cv::line(image, pixel(person.points[i - 1].position), pixel(person.points[i].position),
               cv::Scalar(200, 80, 0), std::max(1, scale));
    }
  }
  for (const scene::DoorEntity& door : entities.doors) {
    cv::line(image, pixel(door.hinge), pixel(door.latch), cv::Scalar(160, 40, 160),
             std::max(2, scale + 1));
    cv::circle(image, pixel(door.hinge), 2 * scale + 1, cv::Scalar(160, 40, 160), -1);
  }
  return grid::WriteImageFile(path, image);
}

}  // namespace fleetmap::cli
