#include "common/vector_map/vectorizer.hpp"

#include <cmath>
#include <numbers>
#include <vector>

#include "common/vector_map/cell_frame.hpp"
#include "common/vector_map/cell_polyline.hpp"
#include "common/vector_map/cell_raster.hpp"
#include "common/vector_map/default_vectorizer.hpp"
#include "common/vector_map/end_extender.hpp"
#include "common/vector_map/free_space_extractor.hpp"
#include "common/vector_map/half_width.hpp"
#include "common/vector_map/lattice.hpp"
#include "common/vector_map/line_refit.hpp"
#include "common/vector_map/painted_cells.hpp"
#include "common/vector_map/paper_vectorizer.hpp"
#include "common/vector_map/point_collapse.hpp"

namespace fleetmap::vector_map {

double Vectorizer::EpsilonFor(double resolution) const {
  return options_.epsilon > 0.0 ? options_.epsilon : DefaultEpsilon(resolution);
}

StatusOr<VectorMap> Vectorizer::Vectorize(const grid::OccupancyGrid& grid) const {
  return VectorizeTile(grid, FullRect(grid));
}

StatusOr<VectorMap> Vectorizer::VectorizeTile(const grid::OccupancyGrid& grid,
                                              const CellRect& rect) const {
  const double resolution = grid.resolution();
  if (!(resolution > 0.0) || !std::isfinite(resolution)) {
    return InvalidArgumentError("vectorize: grid resolution must be positive and finite");
  }
  const double epsilon = EpsilonFor(resolution);
  const double min_epsilon = resolution * std::numbers::sqrt2 / 2.0 * (1 - 1e-12);
  if (!std::isfinite(epsilon) || epsilon < min_epsilon) {
    return InvalidArgumentError("vectorize: epsilon " + std::to_string(epsilon) +
                                " m is below resolution * sqrt(2) / 2");
  }
  if (!(options_.quantum >= 0.0) || !std::isfinite(options_.quantum)) {
    return InvalidArgumentError("vectorize: quantum must be finite and >= 0");
  }
  const Lattice lattice(options_.quantum, options_.lattice_origin);
  // Every vertex kDefault and kPaper make is a cell centre or a half-cell point (border nodes,
  // segment ends), except line-refit moves and line-end extensions, which are checked after
  // snapping. If the lattice holds those points, snapping moves nothing and the build uses the
  // full epsilon; otherwise epsilon less the largest snapping move, so that both constraints hold
  // after it. (At the default epsilon, sqrt(2) cells, any reduction drops the diagonal neighbours
  // from every epsilon disc: about 10 % more vertices on SLAM maps.)
  const CellFrame frame(grid);
  const bool lattice_holds_cells = lattice.Contains(frame.ToMap(Point2(0.0, 0.0))) &&
                                   lattice.Contains(frame.ToMap(Point2(0.5, 0.0))) &&
                                   lattice.Contains(frame.ToMap(Point2(0.0, 0.5)));
  const double build_epsilon =
      lattice_holds_cells ? epsilon : epsilon - lattice.MaxDisplacement() * (1 + 1e-9);
  if (build_epsilon < min_epsilon) {
    return InvalidArgumentError("vectorize: quantum " + std::to_string(options_.quantum) +
                                " m leaves epsilon below resolution * sqrt(2) / 2");
  }
  if (rect.x0 < 0 || rect.y0 < 0 || rect.width < 0 || rect.height < 0 ||
      rect.x0 + rect.width > grid.width() || rect.y0 + rect.height > grid.height()) {
    return InvalidArgumentError("vectorize: tile rectangle is not inside the " +
                                std::to_string(grid.width()) + " x " +
                                std::to_string(grid.height()) + " grid");
  }
  const double eps_cells = build_epsilon / resolution;
  VectorMap map;
  map.frame_id = options_.frame_id;
  map.resolution = resolution;
  map.epsilon = epsilon;
  if (lattice.enabled()) map.lattice = {lattice.quantum(), options_.lattice_origin};
  if (rect.empty()) return map;

  // A half width in cells as emitted, metres: on a lattice (for the tile codec) rounded up to
  // whole HalfWidthStep(epsilon), which the codec stores exactly.
  const double half_width_step = HalfWidthStep(epsilon);
  auto emitted_half_width = [&](double half_width_cells) {
    const double h = half_width_cells * resolution;
    if (!lattice.enabled()) return h;
    const double steps =
        std::min<double>(kMaxHalfWidthSteps, std::ceil(h / half_width_step - 1e-9));
    return steps * half_width_step;
  };
  std::vector<CellPolyline> polylines;
  std::vector<double> half_widths;
  if (options_.method == VectorizeMethod::kPaper) {
    const Delimitation delimitation(grid, rect, static_cast<int>(std::ceil(eps_cells)) + 3,
                                    options_.thresholds);
    polylines = PaperVectorize(delimitation, rect, eps_cells);
  } else {
    CellRaster raster(grid, rect, DefaultMargin(eps_cells), options_.thresholds);
    polylines = DefaultVectorize(raster, grid, options_.thresholds, eps_cells);
    CollapseToPoints(raster, eps_cells, polylines);
    if (lattice.enabled()) {
      // Half widths are measured from the snapped vertices (what a reader will see).
      for (CellPolyline& polyline : polylines) {
        for (Point2& p : polyline.points) p = frame.ToCell(lattice.Snap(frame.ToMap(p)));
      }
    }
    half_widths = CoveredHalfWidths(raster, polylines, epsilon / resolution, 0.5);
    if (options_.refit_lines) {
      // Centre lines off the cell centres where the band then matches the wall's cells better
      // (walls an even number of cells thick), checked on the snapped result.
      LineRefitOptions refit;
      refit.epsilon = epsilon / resolution;
      refit.min_radius = 0.5;
      if (lattice.enabled()) {
        refit.snap = [&](const Point2& p) { return frame.ToCell(lattice.Snap(frame.ToMap(p))); };
        refit.emitted_half_width = [&](double h) { return emitted_half_width(h) / resolution; };
      }
      RefitLines(raster, refit, polylines, half_widths);
    }
    // Line ends that thinning shortened are lengthened to paint their end cells (checked against
    // the full epsilon on the snapped result), so the free space needs no hole for them.
    EndExtensionOptions ends;
    ends.epsilon = epsilon / resolution;
    ends.min_radius = 0.5;
    if (lattice.enabled()) {
      ends.snap = [&](const Point2& p) { return frame.ToCell(lattice.Snap(frame.ToMap(p))); };
    }
    ExtendLineEnds(raster, half_widths, ends, polylines);
  }
  map.obstacles.reserve(polylines.size());
  for (size_t k = 0; k < polylines.size(); ++k) {
    Polyline out;
    out.closed = polylines[k].closed;
    out.points = std::move(polylines[k].points);  // converted in place (no copy)
    for (Point2& p : out.points) p = lattice.Snap(frame.ToMap(p));
    if (!half_widths.empty()) out.half_width = emitted_half_width(half_widths[k]);
    map.obstacles.push_back(std::move(out));
  }
  if (options_.extract_free_space) {
    const double free_eps = options_.free_epsilon > 0.0 ? options_.free_epsilon : epsilon;
    FreeSpaceOptions free_options;
    free_options.epsilon_cells = free_eps / resolution;
    // The cells the rasterizer will paint for these obstacles, from the emitted (snapped)
    // vertices and half widths, exactly as a reader sees them.
    // Per-thread storage, its point buffers reused across calls (PaintedAndNearCells reads only
    // the points and `closed`).
    thread_local std::vector<CellPolyline> emitted;
    thread_local std::vector<double> radii;
    emitted.resize(map.obstacles.size());
    radii.resize(map.obstacles.size());
    for (size_t k = 0; k < map.obstacles.size(); ++k) {
      emitted[k].points.clear();
      for (const Point2& p : map.obstacles[k].points) emitted[k].points.push_back(frame.ToCell(p));
      emitted[k].closed = map.obstacles[k].closed;
      radii[k] = map.obstacles[k].half_width / resolution;
    }
    // Occupied cells within epsilon of an edge are stood for by the obstacles (the epsilon-error
    // constraint's own bound), so they may join the free space; only farther ones are guarded.
    // Both masks come from one visit of the bands, into per-thread storage (no allocation).
    thread_local std::vector<uint8_t> painted;
    thread_local std::vector<uint8_t> near_obstacles;
    PaintedAndNearCells(rect, emitted, radii, 0.5, epsilon / resolution, &painted, &near_obstacles);
    free_options.painted = &painted;
    free_options.near_obstacles = &near_obstacles;
    // The rings are moved over and converted in place (no copies).
    std::vector<CellPolygon> polygons =
        ExtractFreeSpace(grid, rect, options_.thresholds, free_options);
    map.free_space.reserve(polygons.size());
    for (CellPolygon& polygon : polygons) {
      FreePolygon out;
      out.outer = std::move(polygon.outer);
      for (Point2& p : out.outer) p = lattice.Snap(frame.ToMap(p));
      out.holes = std::move(polygon.holes);
      for (auto& hole : out.holes) {
        for (Point2& p : hole) p = lattice.Snap(frame.ToMap(p));
      }
      map.free_space.push_back(std::move(out));
    }
  }
  return map;
}

void VectorizerOptions::Describe(OptionsPrinter& out) const {
  out.Add("method", method);
  out.Add("epsilon", epsilon);
  out.Add("extract_free_space", extract_free_space);
  out.Add("free_epsilon", free_epsilon);
  out.Nested("thresholds", thresholds);
  out.Add("frame_id", frame_id);
  out.Add("quantum", quantum);
  out.Add("lattice_origin", lattice_origin);
  out.Add("refit_lines", refit_lines);
}

}  // namespace fleetmap::vector_map
