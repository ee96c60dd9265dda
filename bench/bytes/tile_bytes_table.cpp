#include "bench/bytes/tile_bytes_table.hpp"

#include <algorithm>

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

// `names`: the table's baseline columns; a baseline the row did not measure prints "-".
void PrintRow(const std::string& name, const TileBytesComparison& c,
              const std::vector<std::string>& names, bool bold, std::ostream& out) {
  const std::string mark = bold ? "**" : "";
  const std::vector<NamedBytes> baselines = TileBaselines(c.grid.bytes);
  const std::vector<NamedRatio> ratios = c.Ratios();
  out << "| " << name << " | " << TilesText(c);
  for (const std::string& column : names) {
    const auto it = std::find_if(baselines.begin(), baselines.end(),
                                 [&](const NamedBytes& b) { return b.name == column; });
    out << " | " << (it == baselines.end() ? std::string("-") : Kilobytes(it->bytes));
  }
  out << " | " << Kilobytes(c.vector.payload);
  for (const std::string& column : names) {
    const auto it = std::find_if(ratios.begin(), ratios.end(),
                                 [&](const NamedRatio& r) { return r.baseline == column; });
    out << " | " << (it == ratios.end() ? std::string("-") : Ratio(it->ratio));
  }
  const NamedRatio smallest = c.RatioToSmallest();
  out << " | " << mark << Ratio(smallest.ratio) << mark << " (" << smallest.baseline << ") |\n";
}

}  // namespace

void PrintTileBytesTable(const std::vector<NamedComparison>& rows, const std::string& item,
                         std::ostream& out) {
  const bool with_dictionary = std::any_of(rows.begin(), rows.end(), [](const NamedComparison& r) {
    return r.bytes.grid.bytes.zstd19_dict > 0;
  });
  const std::vector<std::string> names = TileBaselineNames(with_dictionary);
  out << "| " << item << " | tiles";
  for (const std::string& name : names) out << " | grid " << name << " KB";
  out << " | vector tiles KB";
  for (const std::string& name : names) out << " | vector / " << name;
  out << " | vector / smallest |\n|---|---";
  for (size_t i = 0; i < 2 * names.size() + 2; ++i) out << "|---";
  out << "|\n";
  TileBytesComparison total;
  for (const NamedComparison& row : rows) {
    PrintRow(row.name, row.bytes, names, false, out);
    total += row.bytes;
  }
  PrintRow("**sum**", total, names, true, out);
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
         "grid_tile_zstd19,grid_tile_lz4,grid_tile_zstd19_dict,vector_tile_bytes,"
         "vector_over_patch_cdr,vector_over_zstd3,vector_over_zstd19,vector_over_lz4,"
         "vector_over_zstd19_dict,smallest_baseline,vector_over_smallest";
}

std::vector<std::string> TileBytesCsvFields(const TileBytesComparison& c) {
  const GridTileBytes& grid = c.grid.bytes;
  std::vector<std::string> fields = {
      std::to_string(c.grid.tiles),    std::to_string(c.vector.tiles),
      std::to_string(grid.raw),        std::to_string(grid.patch_cdr),
      std::to_string(grid.zstd3),      std::to_string(grid.zstd19),
      std::to_string(grid.lz4),        std::to_string(grid.zstd19_dict),
      std::to_string(c.vector.payload)};
  // The dictionary's ratio stays empty when it was not measured.
  for (size_t GridTileBytes::*baseline :
       {&GridTileBytes::patch_cdr, &GridTileBytes::zstd3, &GridTileBytes::zstd19,
        &GridTileBytes::lz4, &GridTileBytes::zstd19_dict}) {
    fields.push_back(grid.*baseline > 0 ? FormatDouble("%.4f", c.RatioTo(baseline)) : "");
  }
  const NamedRatio smallest = c.RatioToSmallest();
  fields.push_back(smallest.baseline);
  fields.push_back(FormatDouble("%.4f", smallest.ratio));
  return fields;
}

}  // namespace fleetmap::bench
