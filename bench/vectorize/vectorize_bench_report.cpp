#include "bench/vectorize/vectorize_bench_report.hpp"

#include <algorithm>
#include <functional>
#include <optional>

#include "bench/bytes/tile_bytes_table.hpp"
#include "bench/report/report_format.hpp"

namespace fleetmap::bench {
namespace {

std::string Ms(double ms) { return FormatDouble(ms < 1.0 ? "%.3f" : "%.1f", ms); }
std::string Ratio(double ratio) { return Fixed(ratio, 2); }
std::string Percent(const std::optional<double>& value) {
  return value ? FormatDouble("%.2f", *value) : "undefined";
}

double SafeRatio(double a, double b) { return b > 0.0 ? a / b : 0.0; }

template <typename Value>
std::vector<double> Collect(const std::vector<VectorizeBenchRow>& rows,
                            const std::function<Value(const VectorizeBenchRow&)>& get) {
  std::vector<double> values;
  for (const VectorizeBenchRow& row : rows) values.push_back(static_cast<double>(get(row)));
  return values;
}

double Sum(const std::vector<double>& values) {
  double sum = 0.0;
  for (double v : values) sum += v;
  return sum;
}

// Median over maps where the metric is defined.
std::optional<double> MedianDefined(const std::vector<VectorizeBenchRow>& rows,
                                    std::optional<double> VectorizeBenchRow::*member) {
  std::vector<double> values;
  for (const VectorizeBenchRow& row : rows) {
    if (row.*member) values.push_back(*(row.*member));
  }
  if (values.empty()) return std::nullopt;
  return Median(std::move(values));
}

std::optional<double> MinDefined(const std::vector<VectorizeBenchRow>& rows,
                                 std::optional<double> VectorizeBenchRow::*member) {
  std::optional<double> min;
  for (const VectorizeBenchRow& row : rows) {
    if (row.*member && (!min || *(row.*member) < *min)) min = row.*member;
  }
  return min;
}

// The bound on one tile update.
constexpr double kTileUpdateTargetMs = 1.0;

size_t TilesWithinTarget(const VectorizeBenchRow& row) {
  return std::count_if(
      row.tile_updates.begin(), row.tile_updates.end(),
      [](const VectorizeBenchRow::TileUpdate& update) { return update.ms <= kTileUpdateTargetMs; });
}

// "<tiles within the target> / <tiles timed>".
std::string TilesWithinText(size_t within, size_t timed) {
  return std::to_string(within) + " / " + std::to_string(timed);
}

bool OursValid(const VectorizeBenchRow& row) {
  return row.ours.check.ok() && row.ours_full.check.ok() && row.vmap_check.ok();
}

// "ok", or "<uncovered points>+<discontinuous segments>".
std::string CheckText(const ConstraintCheck& check) {
  if (check.ok()) return "ok";
  return std::to_string(check.uncovered_points) + "+" +
         std::to_string(check.discontinuous_segments);
}

std::string OursCheckText(const VectorizeBenchRow& row) {
  if (OursValid(row)) return "ok";
  return CheckText(row.ours.check) + "/" + CheckText(row.ours_full.check) + "/" +
         CheckText(row.vmap_check);
}

double VertexRatio(const VectorizeBenchRow& row) {
  return SafeRatio(row.ours.vertices, row.opencv.vertices);
}
double TimeRatio(const VectorizeBenchRow& row) { return SafeRatio(row.ours.ms, row.opencv.ms); }
double BytesRatio(const VectorizeBenchRow& row) { return SafeRatio(row.vmap_zstd, row.grid_zstd); }
double RawBytesRatio(const VectorizeBenchRow& row) {
  return SafeRatio(row.vmap_raw, row.grid_zstd);
}
double TileBytesRatio(const VectorizeBenchRow& row) {
  return row.tile_bytes.RatioTo(&GridTileBytes::zstd19);
}

// The bounds on the vector tiles' bytes over the zstd -19 grid tiles.
constexpr double kTileBytesSummedTarget = 0.5;
constexpr double kTileBytesEveryMapTarget = 0.7;

std::vector<NamedComparison> TileComparisons(const std::vector<VectorizeBenchRow>& rows) {
  std::vector<NamedComparison> comparisons;
  for (const VectorizeBenchRow& row : rows) comparisons.push_back({row.name, row.tile_bytes});
  return comparisons;
}

nlohmann::ordered_json RatioJson(const NamedRatio& ratio) {
  return {{"baseline", ratio.baseline}, {"ratio", ratio.ratio}};
}

nlohmann::ordered_json TileBytesJson(const TileBytesComparison& c) {
  nlohmann::ordered_json ratios = nlohmann::ordered_json::array();
  for (const NamedRatio& ratio : c.Ratios()) ratios.push_back(RatioJson(ratio));
  return {{"grid_tiles", c.grid.tiles},
          {"vector_tiles", c.vector.tiles},
          {"grid",
           {{"raw", c.grid.bytes.raw},
            {"patch_cdr", c.grid.bytes.patch_cdr},
            {"zstd3", c.grid.bytes.zstd3},
            {"zstd19", c.grid.bytes.zstd19},
            {"lz4", c.grid.bytes.lz4},
            {"zstd19_dict", c.grid.bytes.zstd19_dict}}},
          {"vector", c.vector.payload},
          {"vector_over", ratios},
          {"vector_over_smallest", RatioJson(c.RatioToSmallest())}};
}

nlohmann::ordered_json Optional(const std::optional<double>& value) {
  return value ? nlohmann::ordered_json(*value) : nlohmann::ordered_json(nullptr);
}

nlohmann::ordered_json MethodJson(const MethodFigures& figures) {
  return {{"vertices", figures.vertices},
          {"segments", figures.segments},
          {"ms", figures.ms},
          {"uncovered_points", figures.check.uncovered_points},
          {"discontinuous_segments", figures.check.discontinuous_segments},
          {"valid", figures.check.ok()}};
}

void PrintVertexBreakdown(const std::vector<VectorizeBenchRow>& rows, std::ostream& out) {
  VertexBreakdown total;
  for (const VectorizeBenchRow& row : rows) total += row.vertices_by_component;
  int64_t opencv_sum = 0;
  for (int64_t v : total.opencv_vertices) opencv_sum += v;
  out << "\nWhere the vertices go, all maps (occupied cells' 8-connected components by size; a "
         "vertex of ours counts for the component of its nearest occupied cell):\n\n"
      << "| component cells | components | OpenCV V | ours V | ours / CV | share of OpenCV's V |\n"
      << "|---|---|---|---|---|---|\n";
  for (size_t c = 0; c < kComponentClasses; ++c) {
    out << "| " << ComponentClassName(c) << " | " << total.components[c] << " | "
        << total.opencv_vertices[c] << " | " << total.ours_vertices[c] << " | "
        << Ratio(SafeRatio(total.ours_vertices[c], total.opencv_vertices[c])) << " | "
        << FormatDouble("%.1f %%", 100.0 * SafeRatio(total.opencv_vertices[c], opencv_sum))
        << " |\n";
  }
  if (total.ours_unattributed > 0) {
    out << "| (no occupied cell within epsilon) | | | " << total.ours_unattributed << " | | |\n";
  }
}

nlohmann::ordered_json VertexBreakdownJson(const VertexBreakdown& breakdown) {
  nlohmann::ordered_json classes = nlohmann::ordered_json::array();
  for (size_t c = 0; c < kComponentClasses; ++c) {
    classes.push_back({{"component_cells", ComponentClassName(c)},
                       {"components", breakdown.components[c]},
                       {"opencv_vertices", breakdown.opencv_vertices[c]},
                       {"ours_vertices", breakdown.ours_vertices[c]}});
  }
  return {{"classes", classes}, {"ours_unattributed", breakdown.ours_unattributed}};
}

}  // namespace

std::vector<BenchTarget> EvaluateVectorizeTargets(const std::vector<VectorizeBenchRow>& rows) {
  using Row = VectorizeBenchRow;
  std::vector<BenchTarget> targets;
  const auto all = [&rows](const std::function<bool(const Row&)>& test) {
    return std::all_of(rows.begin(), rows.end(), test);
  };
  const auto max_of = [&rows](const std::function<double(const Row&)>& get) {
    double max = 0.0;
    for (const Row& row : rows) max = std::max(max, get(row));
    return max;
  };
  int valid = 0;
  for (const Row& row : rows) valid += OursValid(row) ? 1 : 0;
  targets.push_back({"constraints hold on every output of ours (obstacles, full, .vmap)",
                     std::to_string(valid) + " of " + std::to_string(rows.size()) + " maps",
                     all(OursValid)});
  const double vertex_sum_ratio =
      SafeRatio(Sum(Collect<size_t>(rows, [](const Row& r) { return r.ours.vertices; })),
                Sum(Collect<size_t>(rows, [](const Row& r) { return r.opencv.vertices; })));
  targets.push_back(
      {"vertices <= 0.6 x OpenCV, summed", Ratio(vertex_sum_ratio), vertex_sum_ratio <= 0.6});
  const double worst_vertex = max_of(VertexRatio);
  targets.push_back(
      {"vertices <= 1.0 x OpenCV, every map", "worst " + Ratio(worst_vertex), worst_vertex <= 1.0});
  const double worst_time = max_of(TimeRatio);
  targets.push_back({"time (obstacles) <= 1.0 x OpenCV, every map", "worst " + Ratio(worst_time),
                     worst_time <= 1.0});
  double slowest_tile = max_of([](const Row& r) { return r.revectorize_tile_ms; });
  size_t tiles_within = 0;
  size_t tiles_timed = 0;
  for (const Row& row : rows) {
    for (const auto& update : row.tile_updates) slowest_tile = std::max(slowest_tile, update.ms);
    tiles_within += TilesWithinTarget(row);
    tiles_timed += row.tile_updates.size();
  }
  targets.push_back({"re-vectorize one 10 m tile <= 1 ms, every tile",
                     "slowest " + Ms(slowest_tile) + " ms; " +
                         TilesWithinText(tiles_within, tiles_timed) + " tiles within",
                     slowest_tile <= kTileUpdateTargetMs});
  TileBytesComparison tile_total;
  for (const Row& row : rows) tile_total += row.tile_bytes;
  const double tile_sum_ratio = tile_total.RatioTo(&GridTileBytes::zstd19);
  std::string tiles_text = "grid zstd -19 tiles (";
  tiles_text.append(FormatDouble("%g", rows.empty() ? 0.0 : rows.front().tile_size))
      .append(" m, each alone)");
  targets.push_back({std::string("vector tiles <= 0.5 x ").append(tiles_text).append(", summed"),
                     Ratio(tile_sum_ratio), tile_sum_ratio <= kTileBytesSummedTarget});
  const auto worst_tile = std::max_element(
      rows.begin(), rows.end(),
      [](const Row& a, const Row& b) { return TileBytesRatio(a) < TileBytesRatio(b); });
  const double worst_tile_ratio = worst_tile == rows.end() ? 0.0 : TileBytesRatio(*worst_tile);
  targets.push_back({std::string("vector tiles <= 0.7 x ").append(tiles_text).append(", every map"),
                     "worst " + Ratio(worst_tile_ratio) +
                         (worst_tile == rows.end() ? "" : " (" + worst_tile->name + ")"),
                     worst_tile_ratio <= kTileBytesEveryMapTarget});
  const double worst_bytes = max_of(BytesRatio);
  targets.push_back({"whole map in one piece: .vmap zstd -19 <= 0.5 x grid zstd -19, every map",
                     "worst " + Ratio(worst_bytes), worst_bytes <= 0.5});
  const double worst_raw_bytes = max_of(RawBytesRatio);
  targets.push_back({"whole map in one piece: .vmap <= 0.5 x grid zstd -19, every map",
                     "worst " + Ratio(worst_raw_bytes), worst_raw_bytes <= 0.5});
  for (const auto& [name, member] :
       std::vector<std::pair<std::string, std::optional<double> Row::*>>{
           {"MS", &Row::round_trip_ms},
           {"OPDF", &Row::round_trip_opdf},
           {"UPDF", &Row::round_trip_updf}}) {
    const std::optional<double> min = MinDefined(rows, member);
    targets.push_back({"round-trip " + name + " >= 99 %, every map", "worst " + Percent(min),
                       min.has_value() && *min >= 99.0});
  }
  return targets;
}

void PrintVectorizeBenchTables(const std::vector<VectorizeBenchRow>& rows, std::ostream& out) {
  using Row = VectorizeBenchRow;
  out << "| map | cells | ours V | paper V | OpenCV V | V ours/CV | ours ms (obstacles) | ours ms "
         "(full) | paper ms | OpenCV ms | t ours/CV | constraints ours / paper / OpenCV |\n"
      << "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const Row& r : rows) {
    out << "| " << r.name << " | " << r.cells << " | " << r.ours.vertices << " | "
        << r.paper.vertices << " | " << r.opencv.vertices << " | " << Ratio(VertexRatio(r)) << " | "
        << Ms(r.ours.ms) << " | " << Ms(r.ours_full.ms) << " | " << Ms(r.paper.ms) << " | "
        << Ms(r.opencv.ms) << " | " << Ratio(TimeRatio(r)) << " | " << OursCheckText(r) << " / "
        << CheckText(r.paper.check) << " / " << CheckText(r.opencv.check) << " |\n";
  }
  const auto sum = [&rows](const std::function<double(const Row&)>& get) {
    return Sum(Collect<double>(rows, get));
  };
  const double ours_v = sum([](const Row& r) { return r.ours.vertices; });
  const double cv_v = sum([](const Row& r) { return r.opencv.vertices; });
  int valid = 0;
  for (const Row& r : rows) valid += OursValid(r) ? 1 : 0;
  out << "| **sum / median** | " << static_cast<int64_t>(sum([](const Row& r) { return r.cells; }))
      << " | **" << static_cast<int64_t>(ours_v) << "** | "
      << static_cast<int64_t>(sum([](const Row& r) { return r.paper.vertices; })) << " | **"
      << static_cast<int64_t>(cv_v) << "** | **" << Ratio(SafeRatio(ours_v, cv_v)) << "** | "
      << Ms(sum([](const Row& r) { return r.ours.ms; })) << " | "
      << Ms(sum([](const Row& r) { return r.ours_full.ms; })) << " | "
      << Ms(sum([](const Row& r) { return r.paper.ms; })) << " | "
      << Ms(sum([](const Row& r) { return r.opencv.ms; })) << " | med "
      << Ratio(Median(Collect<double>(rows, TimeRatio))) << " | ours ok on " << valid << "/"
      << rows.size() << " |\n\n";

  out << "Bytes per fleet tile (" << FormatDouble("%g", rows.empty() ? 0.0 : rows.front().tile_size)
      << " m), each tile alone, as the wire sends them: the grid tile as a "
         "map_msgs/OccupancyGridUpdate sample (patch CDR) or its cells compressed alone (zstd -3, "
         "zstd -19, LZ4 block); vector tiles = the .vmap's tiles as the VectorTile samples a "
         "robot agent publishes. Ratios below 1: the vector tiles are smaller.\n\n";
  PrintTileBytesTable(TileComparisons(rows), "map", out);

  out << "\nThe whole map in one piece, as files: the grid compressed whole (zstd -19) and as "
         "map_server's PNG, the .vmap as `fleetmap vectorize` writes it (and zstd -19 of it), "
         "the round trip and one-tile updates.\n\n"
      << "| map | grid zstd -19 KB | grid PNG KB | .vmap obstacles KB | .vmap KB | .vmap zstd -19 "
         "KB | .vmap zstd / grid zstd | round-trip MS | OPDF | UPDF | busiest tile update ms | "
         "tiles updated <= 1 ms |\n"
      << "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const Row& r : rows) {
    out << "| " << r.name << " | " << Kilobytes(r.grid_zstd) << " | " << Kilobytes(r.grid_png)
        << " | " << Kilobytes(r.vmap_obstacles_raw) << " | " << Kilobytes(r.vmap_raw) << " | "
        << Kilobytes(r.vmap_zstd) << " | " << Ratio(BytesRatio(r)) << " | "
        << Percent(r.round_trip_ms) << " | " << Percent(r.round_trip_opdf) << " | "
        << Percent(r.round_trip_updf) << " | " << Ms(r.revectorize_tile_ms) << " | "
        << TilesWithinText(TilesWithinTarget(r), r.tile_updates.size()) << " |\n";
  }
  const auto kb_sum = [&](const std::function<double(const Row&)>& get) {
    return Kilobytes(static_cast<size_t>(sum(get)));
  };
  const double vmap_zstd = sum([](const Row& r) { return r.vmap_zstd; });
  const double grid_zstd = sum([](const Row& r) { return r.grid_zstd; });
  out << "| **sum / median** | " << kb_sum([](const Row& r) { return r.grid_zstd; }) << " | "
      << kb_sum([](const Row& r) { return r.grid_png; }) << " | "
      << kb_sum([](const Row& r) { return r.vmap_obstacles_raw; }) << " | "
      << kb_sum([](const Row& r) { return r.vmap_raw; }) << " | "
      << kb_sum([](const Row& r) { return r.vmap_zstd; }) << " | "
      << Ratio(SafeRatio(vmap_zstd, grid_zstd)) << " | med "
      << Percent(MedianDefined(rows, &Row::round_trip_ms)) << " | med "
      << Percent(MedianDefined(rows, &Row::round_trip_opdf)) << " | med "
      << Percent(MedianDefined(rows, &Row::round_trip_updf)) << " | med "
      << Ms(Median(Collect<double>(rows, [](const Row& r) { return r.revectorize_tile_ms; })))
      << " | "
      << TilesWithinText(static_cast<size_t>(sum([](const Row& r) {
                           return static_cast<double>(TilesWithinTarget(r));
                         })),
                         static_cast<size_t>(sum([](const Row& r) {
                           return static_cast<double>(r.tile_updates.size());
                         })))
      << " |\n";
  PrintVertexBreakdown(rows, out);
}

void PrintVectorizeTargets(const std::vector<BenchTarget>& targets, std::ostream& out) {
  out << "\n| target | measured | |\n|---|---|---|\n";
  for (const BenchTarget& target : targets) {
    out << "| " << target.name << " | " << target.actual << " | "
        << (target.met ? "met" : "**missed**") << " |\n";
  }
}

nlohmann::ordered_json VectorizeBenchJson(const std::vector<VectorizeBenchRow>& rows,
                                          const std::vector<BenchTarget>& targets,
                                          const VectorizeBenchOptions& options) {
  nlohmann::ordered_json json;
  json["runs"] = options.runs;
  json["tile_size"] = options.tile_size;
  json["maps"] = nlohmann::ordered_json::array();
  for (const VectorizeBenchRow& r : rows) {
    nlohmann::ordered_json map;
    map["name"] = r.name;
    map["cells"] = r.cells;
    map["resolution"] = r.resolution;
    map["epsilon"] = r.epsilon;
    map["ours_obstacles"] = MethodJson(r.ours);
    map["ours_full"] = MethodJson(r.ours_full);
    map["paper"] = MethodJson(r.paper);
    map["opencv"] = MethodJson(r.opencv);
    map["opencv"]["mask_ms"] = r.opencv_mask_ms;
    map["vmap"] = {{"tiles", r.vmap_tiles},
                   {"raw", r.vmap_raw},
                   {"zstd", r.vmap_zstd},
                   {"obstacles_raw", r.vmap_obstacles_raw},
                   {"obstacles_zstd", r.vmap_obstacles_zstd},
                   {"dropped_free_rings", r.vmap_dropped_free_rings},
                   {"uncovered_points", r.vmap_check.uncovered_points},
                   {"discontinuous_segments", r.vmap_check.discontinuous_segments},
                   {"valid", r.vmap_check.ok()}};
    map["grid"] = {{"raw", r.grid_raw}, {"zstd", r.grid_zstd}, {"png", r.grid_png}};
    map["tile_bytes"] = TileBytesJson(r.tile_bytes);
    map["round_trip"] = {{"MS", Optional(r.round_trip_ms)},
                         {"OPDF", Optional(r.round_trip_opdf)},
                         {"UPDF", Optional(r.round_trip_updf)}};
    map["vertices_by_component"] = VertexBreakdownJson(r.vertices_by_component);
    map["revectorize_tile"] = {{"tile", {r.changed_tile.x, r.changed_tile.y}},
                               {"changed_cells", r.changed_cells},
                               {"ms", r.revectorize_tile_ms},
                               {"tiles_within_1ms", TilesWithinTarget(r)},
                               {"every_tile", nlohmann::ordered_json::array()}};
    for (const auto& update : r.tile_updates) {
      map["revectorize_tile"]["every_tile"].push_back(
          {{"tile", {update.tile.x, update.tile.y}}, {"ms", update.ms}});
    }
    json["maps"].push_back(std::move(map));
  }
  if (!rows.empty()) {
    const TileBytesHeadline headline = HeadlineOf(TileComparisons(rows));
    json["tile_bytes_headline"] = {{"summed", RatioJson(headline.summed)},
                                   {"worst", RatioJson(headline.worst)},
                                   {"worst_map", headline.worst_map}};
  }
  json["targets"] = nlohmann::ordered_json::array();
  for (const BenchTarget& target : targets) {
    json["targets"].push_back(
        {{"target", target.name}, {"measured", target.actual}, {"met", target.met}});
  }
  return json;
}

std::string VectorizeBenchCsv(const std::vector<VectorizeBenchRow>& rows) {
  std::string csv =
      "map,cells,resolution,epsilon,ours_vertices,ours_segments,ours_ms,ours_valid,"
      "ours_full_vertices,ours_full_ms,ours_full_valid,paper_vertices,paper_segments,paper_ms,"
      "paper_uncovered,paper_discontinuous,opencv_vertices,opencv_segments,opencv_ms,"
      "opencv_mask_ms,opencv_uncovered,opencv_discontinuous,vmap_tiles,vmap_raw,vmap_zstd,"
      "vmap_obstacles_raw,vmap_obstacles_zstd,vmap_valid,grid_raw,grid_zstd,grid_png,"
      "round_trip_ms,round_trip_opdf,round_trip_updf,revectorize_tile_ms,";
  csv.append(TileBytesCsvHeader()).append("\n");
  const auto number = [](double value) { return FormatDouble("%.6g", value); };
  const auto optional = [&number](const std::optional<double>& value) {
    return value ? number(*value) : std::string();
  };
  for (const VectorizeBenchRow& r : rows) {
    const std::vector<std::string> fields = {r.name,
                                             std::to_string(r.cells),
                                             number(r.resolution),
                                             number(r.epsilon),
                                             std::to_string(r.ours.vertices),
                                             std::to_string(r.ours.segments),
                                             number(r.ours.ms),
                                             r.ours.check.ok() ? "1" : "0",
                                             std::to_string(r.ours_full.vertices),
                                             number(r.ours_full.ms),
                                             r.ours_full.check.ok() ? "1" : "0",
                                             std::to_string(r.paper.vertices),
                                             std::to_string(r.paper.segments),
                                             number(r.paper.ms),
                                             std::to_string(r.paper.check.uncovered_points),
                                             std::to_string(r.paper.check.discontinuous_segments),
                                             std::to_string(r.opencv.vertices),
                                             std::to_string(r.opencv.segments),
                                             number(r.opencv.ms),
                                             number(r.opencv_mask_ms),
                                             std::to_string(r.opencv.check.uncovered_points),
                                             std::to_string(r.opencv.check.discontinuous_segments),
                                             std::to_string(r.vmap_tiles),
                                             std::to_string(r.vmap_raw),
                                             std::to_string(r.vmap_zstd),
                                             std::to_string(r.vmap_obstacles_raw),
                                             std::to_string(r.vmap_obstacles_zstd),
                                             r.vmap_check.ok() ? "1" : "0",
                                             std::to_string(r.grid_raw),
                                             std::to_string(r.grid_zstd),
                                             std::to_string(r.grid_png),
                                             optional(r.round_trip_ms),
                                             optional(r.round_trip_opdf),
                                             optional(r.round_trip_updf),
                                             number(r.revectorize_tile_ms)};
    for (size_t i = 0; i < fields.size(); ++i) csv.append(i == 0 ? "" : ",").append(fields[i]);
    for (const std::string& field : TileBytesCsvFields(r.tile_bytes)) csv.append(",").append(field);
    csv += "\n";
  }
  return csv;
}

}  // namespace fleetmap::bench
