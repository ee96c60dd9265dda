#include "common/extrapolation/ply_reader.hpp"

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <vector>

#include "common/core/file_io.hpp"

namespace fleetmap::extrapolation {
namespace {

struct Property {
  std::string name;
  std::string type;
  int size = 0;  // bytes
};

// Bytes of a PLY scalar type, 0 if unknown.
int TypeSize(const std::string& type) {
  if (type == "char" || type == "uchar" || type == "int8" || type == "uint8") return 1;
  if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return 2;
  if (type == "int" || type == "uint" || type == "int32" || type == "uint32") return 4;
  if (type == "float" || type == "float32") return 4;
  if (type == "double" || type == "float64") return 8;
  return 0;
}

bool IsFloatType(const std::string& type) {
  return type == "float" || type == "float32" || type == "double" || type == "float64";
}

}  // namespace

StatusOr<PointCloud> ParsePly(const std::string& bytes, const std::string& source_name,
                              int64_t max_points) {
  auto error = [&](const std::string& what) {
    return InvalidArgumentError(source_name + ": " + what);
  };
  size_t pos = 0;
  int line_number = 0;
  auto next_line = [&](std::string* line) {
    if (pos >= bytes.size()) return false;
    size_t end = bytes.find('\n', pos);
    if (end == std::string::npos) end = bytes.size();
    *line = bytes.substr(pos, end - pos);
    if (!line->empty() && line->back() == '\r') line->pop_back();
    pos = end + 1;
    ++line_number;
    return true;
  };

  std::string line;
  if (!next_line(&line) || line != "ply") return error("not a PLY file (no 'ply' magic line)");
  bool ascii = false, have_format = false, in_vertex = false, seen_vertex = false;
  int64_t count = 0;
  std::vector<Property> properties;
  while (true) {
    if (!next_line(&line)) return error("the header has no 'end_header'");
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (keyword.empty() || keyword == "comment" || keyword == "obj_info") continue;
    if (keyword == "end_header") break;
    if (keyword == "format") {
      std::string format, version;
      words >> format >> version;
      if (format == "ascii") {
        ascii = true;
      } else if (format == "binary_little_endian") {
        ascii = false;
      } else if (format == "binary_big_endian") {
        return error("binary_big_endian PLY is not supported (use ascii or binary_little_endian)");
      } else {
        return error("unknown format '" + format + "' on line " + std::to_string(line_number));
      }
      if (version != "1.0") return error("unsupported PLY version '" + version + "'");
      have_format = true;
    } else if (keyword == "element") {
      std::string name, count_text;
      words >> name >> count_text;
      if (seen_vertex) {
        in_vertex = false;  // elements after the vertices are not read
        continue;
      }
      if (name != "vertex") {
        return error("element '" + name + "' comes before 'vertex' (the vertices must be first)");
      }
      char* end = nullptr;
      count = std::strtoll(count_text.c_str(), &end, 10);
      if (count_text.empty() || *end != '\0' || count < 0) {
        return error("bad vertex count '" + count_text + "'");
      }
      if (count > max_points) {
        return ResourceExhaustedError(source_name + ": " + std::to_string(count) +
                                      " vertices, more than the limit of " +
                                      std::to_string(max_points));
      }
      in_vertex = true;
      seen_vertex = true;
    } else if (keyword == "property") {
      if (!in_vertex) {
        if (!seen_vertex) return error("a property comes before any element");
        continue;
      }
      std::string type, name;
      words >> type;
      if (type == "list") return error("list properties on vertices are not supported");
      words >> name;
      const int size = TypeSize(type);
      if (size == 0 || name.empty()) {
        return error("bad property on line " + std::to_string(line_number) + ": '" + line + "'");
      }
      properties.push_back({name, type, size});
    } else {
      return error("unknown header line " + std::to_string(line_number) + ": '" + line + "'");
    }
  }
  if (!have_format) return error("the header has no 'format' line");
  if (!seen_vertex) return error("no 'vertex' element");
  int index[3] = {-1, -1, -1};
  size_t offset[3] = {0, 0, 0};
  size_t stride = 0;
  for (size_t i = 0; i < properties.size(); ++i) {
    for (int axis = 0; axis < 3; ++axis) {
      if (properties[i].name == std::string(1, static_cast<char>('x' + axis))) {
        if (!IsFloatType(properties[i].type)) {
          return error("vertex property '" + properties[i].name + "' is " + properties[i].type +
                       ", not float or double");
        }
        index[axis] = static_cast<int>(i);
        offset[axis] = stride;
      }
    }
    stride += properties[i].size;
  }
  for (int axis = 0; axis < 3; ++axis) {
    if (index[axis] < 0) {
      return error(std::string("the vertices have no '") + static_cast<char>('x' + axis) +
                   "' property");
    }
  }

  PointCloud cloud;
  cloud.reserve(static_cast<size_t>(count));
  if (ascii) {
    for (int64_t v = 0; v < count; ++v) {
      if (!next_line(&line)) {
        return error("truncated: " + std::to_string(v) + " of " + std::to_string(count) +
                     " vertices");
      }
      std::istringstream words(line);
      Point3 p;
      for (size_t i = 0; i < properties.size(); ++i) {
        std::string token;
        if (!(words >> token)) {
          return error("vertex " + std::to_string(v) + " (line " + std::to_string(line_number) +
                       ") has too few values");
        }
        for (int axis = 0; axis < 3; ++axis) {
          if (static_cast<int>(i) != index[axis]) continue;
          char* end = nullptr;
          p[axis] = std::strtod(token.c_str(), &end);
          if (*end != '\0') {
            return error("vertex " + std::to_string(v) + ": '" + token + "' is not a number");
          }
        }
      }
      if (!p.allFinite()) return error("vertex " + std::to_string(v) + " is not finite");
      cloud.push_back(p);
    }
    return cloud;
  }
  const size_t needed = static_cast<size_t>(count) * stride;
  if (bytes.size() - std::min(pos, bytes.size()) < needed) {
    return error("truncated: the header announces " + std::to_string(count) + " vertices (" +
                 std::to_string(needed) + " bytes), the file holds " +
                 std::to_string(bytes.size() - std::min(pos, bytes.size())) + " bytes");
  }
  const char* data = bytes.data() + pos;
  for (int64_t v = 0; v < count; ++v) {
    const char* vertex = data + static_cast<size_t>(v) * stride;
    Point3 p;
    for (int axis = 0; axis < 3; ++axis) {
      if (properties[index[axis]].size == 4) {
        float f;
        std::memcpy(&f, vertex + offset[axis], 4);
        p[axis] = f;
      } else {
        std::memcpy(&p[axis], vertex + offset[axis], 8);
      }
    }
    if (!p.allFinite()) return error("vertex " + std::to_string(v) + " is not finite");
    cloud.push_back(p);
  }
  return cloud;
}

StatusOr<PointCloud> ReadPly(const std::string& path, int64_t max_points) {
  std::ifstream file(path, std::ios::binary);
  if (!file) return NotFoundError(path + ": cannot open the point cloud");
  std::ostringstream bytes;
  bytes << file.rdbuf();
  return ParsePly(bytes.str(), path, max_points);
}

Status WritePly(const PointCloud& cloud, const std::string& path, bool ascii) {
  std::ostringstream file;
  file << "ply\nformat " << (ascii ? "ascii" : "binary_little_endian")
       << " 1.0\ncomment fleetmap point cloud, map frame, metres\nelement vertex " << cloud.size()
       << "\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
  for (const Point3& p : cloud) {
    if (ascii) {
      file << static_cast<float>(p.x()) << " " << static_cast<float>(p.y()) << " "
           << static_cast<float>(p.z()) << "\n";
    } else {
      const float xyz[3] = {static_cast<float>(p.x()), static_cast<float>(p.y()),
                            static_cast<float>(p.z())};
      file.write(reinterpret_cast<const char*>(xyz), sizeof(xyz));
    }
  }
  return WriteFileAtomically(path, file.str());
}

}  // namespace fleetmap::extrapolation
