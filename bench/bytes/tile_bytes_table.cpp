#include "bench/bytes/tile_bytes_table.hpp"

#include "bench/report/report_format.hpp"

namespace fleetmap::bench {
namespace {

std::string Ratio(double ratio) { return Fixed(ratio, 2); }

// "12" when both sides sent the same tiles, else "grid 12 / vector 11".
std::string TilesText(const TileBytesComparison& c) {
  if (c.grid.tiles == c.vector.tiles) return std::to_string(c.grid.tiles);
  std::string text = "grid ";
  text.append(std::to_string(c.grid.tiles)).append(" / vector ");
  return text.append(std::to_string(c.vector.tiles));
}

void PrintRow(const std::string& name, const TileBytesComparison& c, bool bold, std::ostream& out) {
  const std::string mark = bold ? "**" : "";
  out << "| " << name << " | " << TilesText(c);
  for (const NamedBytes& baseline : TileBaselines(c.grid.bytes))
    out << " | " << Kilobytes(baseline.bytes);
  out << " | " << Kilobytes(c.vector.payload);
  for (const NamedRatio& ratio : c.Ratios()) out << " | " << Ratio(ratio.ratio);
  const NamedRatio smallest = c.RatioToSmallest();
  out << " | " << mark << Ratio(smallest.ratio) << mark << " (" << smallest.baseline << ") |\n";
}

}  // namespace

void PrintTileBytesTable(const std::vector<NamedComparison>& rows, const std::string& item,
                         std::ostream& out) {
  const std::vector<std::string> names = TileBaselineNames();
  out << "| " << item << " | tiles";
  for (const std::string& name : names) out << " | grid " << name << " KB";
  out << " | vector tiles KB";
  for (const std::string& name : names) out << " | vector / " << name;
  out << " | vector / smallest |\n|---|---";
  for (size_t i = 0; i < 2 * names.size() + 2; ++i) out << "|---";
  out << "|\n";
  TileBytesComparison total;
  for (const NamedComparison& row : rows) {
    PrintRow(row.name, row.bytes, false, out);
    total += row.bytes;
  }
  PrintRow("**sum**", total, true, out);
  out << "\n" << HeadlineText(HeadlineOf(rows), item) << "\n";
}

std::string HeadlineText(const TileBytesHeadline& headline, const std::string& item) {
  std::string text = "Vector tiles / smallest baseline: **";
  text.append(Ratio(headline.summed.ratio)).append("** summed (vs ");
  text.append(headline.summed.baseline).append("); worst ").append(item).append(" **");
  text.append(Ratio(headline.worst.ratio)).append("** (").append(headline.worst_map);
  return text.append(", vs ").append(headline.worst.baseline).append(").");
}

std::string TileBytesCsvHeader() {
  return "grid_tiles,vector_tiles,grid_tile_raw,grid_tile_patch_cdr,grid_tile_zstd3,"
         "grid_tile_zstd19,grid_tile_lz4,vector_tile_bytes,vector_over_patch_cdr,"
         "vector_over_zstd3,vector_over_zstd19,vector_over_lz4,smallest_baseline,"
         "vector_over_smallest";
}

std::vector<std::string> TileBytesCsvFields(const TileBytesComparison& c) {
  std::vector<std::string> fields = {
      std::to_string(c.grid.tiles),       std::to_string(c.vector.tiles),
      std::to_string(c.grid.bytes.raw),   std::to_string(c.grid.bytes.patch_cdr),
      std::to_string(c.grid.bytes.zstd3), std::to_string(c.grid.bytes.zstd19),
      std::to_string(c.grid.bytes.lz4),   std::to_string(c.vector.payload)};
  for (const NamedRatio& ratio : c.Ratios()) fields.push_back(FormatDouble("%.4f", ratio.ratio));
  const NamedRatio smallest = c.RatioToSmallest();
  fields.push_back(smallest.baseline);
  fields.push_back(FormatDouble("%.4f", smallest.ratio));
  return fields;
}

}  // namespace fleetmap::bench
