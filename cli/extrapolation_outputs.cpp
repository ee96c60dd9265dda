#include "cli/extrapolation_outputs.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <opencv2/imgproc.hpp>

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

// Polygons of the free cells of `grid` whose map-frame cell centres come from `map_from_grid`.
nlohmann::json FreePolygons(const grid::OccupancyGrid& grid, const Transform2& map_from_grid) {
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
    nlohmann::json coordinates = nlohmann::json::array();
    for (const cv::Point& p : contour) {
      const Point2 c = map_from_grid * grid.CellCenter(p.x, p.y);
      coordinates.push_back({c.x(), c.y()});
    }
    coordinates.push_back(coordinates.front());  // GeoJSON rings are closed
    return coordinates;
  };
  nlohmann::json polygons = nlohmann::json::array();
  for (size_t i = 0; i < contours.size(); ++i) {
    if (hierarchy[i][3] >= 0) continue;  // a hole: added with its outer ring
    nlohmann::json rings = nlohmann::json::array({ring(contours[i])});
    for (int child = hierarchy[i][2]; child >= 0; child = hierarchy[child][0]) {
      rings.push_back(ring(contours[child]));
    }
    polygons.push_back(rings);
  }
  return polygons;
}

}  // namespace

nlohmann::json PredictedFreeGeoJson(const extrapolation::ExtrapolationResult& result, double p_th) {
  nlohmann::json features = nlohmann::json::array();
  auto add = [&](const nlohmann::json& polygons, nlohmann::json properties) {
    properties["p_th"] = p_th;
    for (const nlohmann::json& rings : polygons) {
      features.push_back({{"type", "Feature"},
                          {"geometry", {{"type", "Polygon"}, {"coordinates", rings}}},
                          {"properties", properties}});
    }
  };
  for (const Submap& s : result.graph.submaps) {
    if (s.kind != SubmapKind::kObserved) {
      add(FreePolygons(s.navigable, s.map_from_submap.ToTransform()),
          {{"submap", s.id},
           {"kind", scene::SubmapKindName(s.kind)},
           {"class", ClassOf(s.kind)},
           {"entities", s.entity_ids},
           {"elevation", s.elevation}});
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
    add(FreePolygons(people, map_from_submap), {{"submap", s.id},
                                                {"kind", "conditionally_free"},
                                                {"class", "dynamic"},
                                                {"entities", s.entity_ids},
                                                {"elevation", 0.0}});
  }
  return {{"type", "FeatureCollection"}, {"features", features}};
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
