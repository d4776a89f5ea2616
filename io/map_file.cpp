// ROS map_server PGM + YAML maps; see map_file.hpp.
#include "io/map_file.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <vector>

#include "io/atomic_file.hpp"
#include "sensor/input_error.hpp"

namespace lifelong::io {
namespace {

constexpr unsigned char kOccupied = 0, kFree = 254, kUnknownPixel = 205;

/// Shortest text that reads back to the same double (std::to_chars, locale-independent).
std::string Shortest(double v) {
  char buf[64];
  const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
  return ec == std::errc() ? std::string(buf, end) : "nan";
}

double ParseNumber(std::string token, const std::string& path, int line, const std::string& field) {
  while (!token.empty() && (token.back() == ' ' || token.back() == '\r')) token.pop_back();
  while (!token.empty() && token.front() == ' ') token.erase(0, 1);
  double v = 0.0;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), v);
  if (ec != std::errc() || end != token.data() + token.size() || !std::isfinite(v)) {
    throw InputError(path, line, field, "not a finite number: '" + token + "'");
  }
  return v;
}

/// The flat `key: value` subset of YAML that map_server files use, with line numbers.
struct YamlEntry {
  std::string value;
  int line = 0;
};
std::map<std::string, YamlEntry> ReadFlatYaml(std::istream& in, const std::string& path) {
  std::map<std::string, YamlEntry> entries;
  std::string text;
  for (int line = 1; std::getline(in, text); ++line) {
    if (line == std::numeric_limits<int>::max()) throw InputError(path, line, "", "too many lines");
    const std::size_t hash = text.find('#');
    if (hash != std::string::npos) text.resize(hash);
    if (text.find_first_not_of(" \t\r") == std::string::npos) continue;
    const std::size_t colon = text.find(':');
    if (colon == std::string::npos) throw InputError(path, line, "", "expected 'key: value'");
    const std::size_t b = text.find_first_not_of(" \t", colon + 1);
    const std::size_t e = text.find_last_not_of(" \t\r");
    std::string value = b == std::string::npos ? "" : text.substr(b, e - b + 1);
    if (value.size() >= 2 && (value[0] == '"' || value[0] == '\'') && value.back() == value[0])
      value = value.substr(1, value.size() - 2);
    const std::size_t kb = text.find_first_not_of(" \t");
    entries[text.substr(kb, colon - kb)] = {value, line};
  }
  if (in.bad()) throw InputError(path, 0, "", "read error");
  return entries;
}

const YamlEntry& Require(const std::map<std::string, YamlEntry>& yaml, const std::string& key,
                         const std::string& path) {
  const auto it = yaml.find(key);
  if (it == yaml.end()) throw InputError(path, 0, key, "missing");
  return it->second;
}

/// `[x, y, yaw]` with yaw 0: the map's lower-left corner.
void ParseOrigin(const YamlEntry& origin, const std::string& path, MapYaml* out) {
  const std::string& list = origin.value;
  if (list.size() < 2 || list.front() != '[' || list.back() != ']') {
    throw InputError(path, origin.line, "origin", "expected [x, y, yaw]");
  }
  std::vector<double> xyz;
  std::istringstream items(list.substr(1, list.size() - 2));
  for (std::string item; std::getline(items, item, ',');) {
    xyz.push_back(ParseNumber(item, path, origin.line, "origin"));
  }
  if (xyz.size() != 3) throw InputError(path, origin.line, "origin", "expected [x, y, yaw]");
  if (xyz[2] != 0.0) throw InputError(path, origin.line, "origin", "rotated maps unsupported");
  out->origin_x_m = xyz[0];
  out->origin_y_m = xyz[1];
}

std::string Directory(const std::string& path) {
  const std::size_t slash = path.rfind('/');
  return slash == std::string::npos ? "" : path.substr(0, slash + 1);
}

bool IsSpace(int c) { return c != EOF && std::isspace(c); }

/// The next PGM header token: skips whitespace and `#` comments (to the end of the line),
/// and consumes the one whitespace byte after the token.
std::string HeaderToken(std::istream& in, const std::string& path, const char* field) {
  int c = in.get();
  for (; c == '#' || IsSpace(c); c = in.get()) {
    if (c != '#') continue;
    while (c != EOF && c != '\n') c = in.get();  // a comment runs to the end of the line
  }
  std::string token;
  for (; c != EOF && !IsSpace(c); c = in.get()) {
    if (token.size() == 32) throw InputError(path, 0, field, "PGM header token too long");
    token.push_back(static_cast<char>(c));
  }
  if (token.empty()) throw InputError(path, 0, field, "truncated PGM header");
  return token;
}

/// A positive decimal integer no larger than `max`.
int HeaderInt(std::istream& in, const std::string& path, const char* field, int max) {
  const std::string token = HeaderToken(in, path, field);
  int v = 0;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), v);
  if (ec != std::errc() || end != token.data() + token.size() || v <= 0 || v > max) {
    throw InputError(path, 0, field,
                     "expected an integer in [1, " + std::to_string(max) + "]: '" + token + "'");
  }
  return v;
}

/// Reads exactly n bytes, in chunks so a header that lies about the size costs no memory.
std::string ReadPixels(std::istream& in, std::size_t n, const std::string& path) {
  constexpr std::size_t kChunk = std::size_t{1} << 20;
  std::string pixels;
  while (pixels.size() < n) {
    const std::size_t old = pixels.size(), want = std::min(kChunk, n - old);
    pixels.resize(old + want);
    if (!in.read(&pixels[old], static_cast<std::streamsize>(want))) {
      throw InputError(path, 0, "pixels", "fewer pixels than width*height");
    }
  }
  return pixels;
}

}  // namespace

MapYaml ParseMapYaml(std::istream& in, const std::string& path) {
  const auto yaml = ReadFlatYaml(in, path);
  auto number = [&](const std::string& key, double fallback) {
    const auto it = yaml.find(key);
    return it == yaml.end() ? fallback : ParseNumber(it->second.value, path, it->second.line, key);
  };
  const auto mode = yaml.find("mode");
  if (mode != yaml.end() && mode->second.value != "trinary") {
    throw InputError(path, mode->second.line, "mode", "only 'trinary' maps are supported");
  }
  MapYaml out;
  ParseOrigin(Require(yaml, "origin", path), path, &out);
  const YamlEntry& resolution = Require(yaml, "resolution", path);
  out.resolution_m = ParseNumber(resolution.value, path, resolution.line, "resolution");
  if (out.resolution_m <= 0.0) throw InputError(path, resolution.line, "resolution", "must be > 0");
  out.negate = number("negate", 0.0) != 0.0;
  out.thresholds.occupied_thresh = number("occupied_thresh", 0.65);
  out.thresholds.free_thresh = number("free_thresh", 0.196);
  const YamlEntry& image = Require(yaml, "image", path);
  if (image.value.empty()) throw InputError(path, image.line, "image", "empty");
  out.image = image.value;
  out.image_line = image.line;
  return out;
}

OccupancyGrid ParsePgmImage(std::istream& in, const std::string& path, const MapYaml& yaml) {
  if (HeaderToken(in, path, "magic") != "P5") {
    throw InputError(path, 1, "magic", "not a binary PGM (P5)");
  }
  constexpr int kMaxInt = std::numeric_limits<int>::max();
  OccupancyGrid grid;
  grid.width = HeaderInt(in, path, "width", kMaxInt);
  grid.height = HeaderInt(in, path, "height", kMaxInt);
  const int maxval = HeaderInt(in, path, "maxval", 255);  // 8-bit P5 only
  const std::size_t n =
      static_cast<std::size_t>(grid.width) * static_cast<std::size_t>(grid.height);
  if (n > static_cast<std::size_t>(kMaxInt)) {
    throw InputError(path, 0, "height", "width*height exceeds 2^31 - 1 cells");
  }
  // The far edges must be finite too: a huge resolution or origin passes the YAML's own
  // checks but would put the map's corner at infinity.
  const double far_x = yaml.origin_x_m + yaml.resolution_m * static_cast<double>(grid.width);
  const double far_y = yaml.origin_y_m + yaml.resolution_m * static_cast<double>(grid.height);
  if (!std::isfinite(far_x) || !std::isfinite(far_y)) {
    throw InputError(path, 0, "resolution", "origin + resolution * size is not finite");
  }
  const std::string pixels = ReadPixels(in, n, path);
  grid.resolution_m = yaml.resolution_m;
  grid.origin_x_m = yaml.origin_x_m;
  grid.origin_y_m = yaml.origin_y_m;
  grid.p_occ.assign(n, OccupancyGrid::kUnknown);
  for (int row = 0; row < grid.height; ++row) {
    for (int col = 0; col < grid.width; ++col) {
      const std::size_t k =
          static_cast<std::size_t>(grid.height - 1 - row) * static_cast<std::size_t>(grid.width) +
          static_cast<std::size_t>(col);
      const double v = static_cast<unsigned char>(pixels[k]) / static_cast<double>(maxval);
      const double p = yaml.negate ? v : 1.0 - v;  // map_server: dark = occupied
      if (p > yaml.thresholds.occupied_thresh)
        grid.At(col, row) = 1.0f;
      else if (p < yaml.thresholds.free_thresh)
        grid.At(col, row) = 0.0f;
    }
  }
  return grid;
}

OccupancyGrid ReadPgmMap(const std::string& yaml_path) {
  std::ifstream yaml_in(yaml_path);
  if (!yaml_in) throw InputError(yaml_path, 0, "", "cannot open file");
  const MapYaml yaml = ParseMapYaml(yaml_in, yaml_path);
  const std::string pgm_path =
      yaml.image.rfind('/', 0) == 0 ? yaml.image : Directory(yaml_path) + yaml.image;
  std::error_code error;  // a too-long or unreadable path is "not found", not an exception
  if (!std::filesystem::is_regular_file(pgm_path, error)) {  // no device, FIFO, folder
    throw InputError(yaml_path, yaml.image_line, "image", "no such image file: " + pgm_path);
  }
  std::ifstream pgm_in(pgm_path, std::ios::binary);
  if (!pgm_in) throw InputError(pgm_path, 0, "", "cannot open file");
  return ParsePgmImage(pgm_in, pgm_path, yaml);
}

MapFilePaths WritePgmMap(const std::string& stem_or_pgm_path, const OccupancyGrid& grid,
                         const MapFileConfig& config) {
  std::string stem = stem_or_pgm_path;
  if (stem.size() > 4 && stem.compare(stem.size() - 4, 4, ".pgm") == 0)
    stem.resize(stem.size() - 4);
  const MapFilePaths paths{stem + ".pgm", stem + ".yaml"};
  std::string pgm =
      "P5\n" + std::to_string(grid.width) + " " + std::to_string(grid.height) + "\n255\n";
  for (int row = grid.height - 1; row >= 0; --row) {  // image row 0 = highest y
    for (int col = 0; col < grid.width; ++col) {
      const float p = grid.At(col, row);
      pgm.push_back(static_cast<char>(p < 0.0f                     ? kUnknownPixel
                                      : p > config.occupied_thresh ? kOccupied
                                      : p < config.free_thresh     ? kFree
                                                                   : kUnknownPixel));
    }
  }
  const std::size_t slash = paths.pgm.rfind('/');
  const std::string yaml =
      "image: " + (slash == std::string::npos ? paths.pgm : paths.pgm.substr(slash + 1)) +
      "\nresolution: " + Shortest(grid.resolution_m) + "\norigin: [" + Shortest(grid.origin_x_m) +
      ", " + Shortest(grid.origin_y_m) +
      ", 0.0]\nnegate: 0\noccupied_thresh: " + Shortest(config.occupied_thresh) +
      "\nfree_thresh: " + Shortest(config.free_thresh) + "\nmode: trinary\n";
  WriteFileAtomically(paths.pgm, pgm);
  WriteFileAtomically(paths.yaml, yaml);
  return paths;
}

}  // namespace lifelong::io
