#include "common/vector_map/svg.hpp"

#include <algorithm>
#include <limits>
#include <sstream>

namespace fleetmap::vector_map {

std::string ToSvg(const VectorMap& map, const SvgOptions& options) {
  double min_x = std::numeric_limits<double>::infinity();
  double min_y = min_x;
  double max_x = -min_x;
  double max_y = -min_x;
  auto grow = [&](const Point2& p) {
    min_x = std::min(min_x, p.x());
    min_y = std::min(min_y, p.y());
    max_x = std::max(max_x, p.x());
    max_y = std::max(max_y, p.y());
  };
  for (const auto& polyline : map.obstacles)
    std::for_each(polyline.points.begin(), polyline.points.end(), grow);
  for (const auto& polygon : map.free_space)
    std::for_each(polygon.outer.begin(), polygon.outer.end(), grow);
  if (min_x > max_x) min_x = min_y = max_x = max_y = 0.0;
  const double margin = map.resolution;
  min_x -= margin;
  min_y -= margin;
  max_x += margin;
  max_y += margin;
  const double s = options.pixels_per_metre;
  auto px = [&](const Point2& p) {
    std::ostringstream out;
    out << (p.x() - min_x) * s << ',' << (max_y - p.y()) * s;
    return out.str();
  };
  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << (max_x - min_x) * s
      << "\" height=\"" << (max_y - min_y) * s << "\">\n";
  svg << "<rect width=\"100%\" height=\"100%\" fill=\"#9a9a9a\"/>\n";
  for (const auto& polygon : map.free_space) {
    svg << "<path fill=\"#f4f4f4\" fill-rule=\"evenodd\" stroke=\"none\" d=\"";
    auto ring = [&](const std::vector<Point2>& points) {
      for (size_t i = 0; i < points.size(); ++i)
        svg << (i == 0 ? "M" : "L") << px(points[i]) << ' ';
      if (!points.empty()) svg << "Z ";
    };
    ring(polygon.outer);
    for (const auto& hole : polygon.holes) ring(hole);
    svg << "\"/>\n";
  }
  for (const auto& polyline : map.obstacles) {
    if (polyline.points.size() == 1) {
      svg << "<circle cx=\"" << (polyline.points[0].x() - min_x) * s << "\" cy=\""
          << (max_y - polyline.points[0].y()) * s << "\" r=\"" << options.stroke_width_px
          << "\" fill=\"#202020\"/>\n";
      continue;
    }
    svg << '<' << (polyline.closed ? "polygon" : "polyline") << " fill=\"none\" stroke=\"#202020\""
        << " stroke-width=\"" << options.stroke_width_px
        << "\" stroke-linejoin=\"round\" points=\"";
    for (const auto& p : polyline.points) svg << px(p) << ' ';
    svg << "\"/>\n";
    if (options.draw_vertices) {
      for (const auto& p : polyline.points) {
        svg << "<circle cx=\"" << (p.x() - min_x) * s << "\" cy=\"" << (max_y - p.y()) * s
            << "\" r=\"" << options.stroke_width_px << "\" fill=\"#d03030\"/>\n";
      }
    }
  }
  svg << "</svg>\n";
  return svg.str();
}

}  // namespace fleetmap::vector_map
