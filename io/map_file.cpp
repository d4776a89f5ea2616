// ROS map_server PGM + YAML maps; see map_file.hpp.
#include "io/map_file.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>

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

void WriteFile(const std::string& path, const std::string& bytes) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary);
    if (!out || !out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()))) {
      throw InputError(path, 0, "", "cannot write file");
    }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw InputError(path, 0, "", "cannot rename the temporary file into place");
  }
}

/// The flat `key: value` subset of YAML that map_server files use, with line numbers.
struct YamlEntry {
  std::string value;
  int line = 0;
};
std::map<std::string, YamlEntry> ReadFlatYaml(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, 0, "", "cannot open file");
  std::map<std::string, YamlEntry> entries;
  std::string text;
  for (int line = 1; std::getline(in, text); ++line) {
    const std::size_t hash = text.find('#');
    if (hash != std::string::npos) text.resize(hash);
    if (text.find_first_not_of(" \t\r") == std::string::npos) continue;
    const std::size_t colon = text.find(':');
    if (colon == std::string::npos) throw InputError(path, line, "", "expected 'key: value'");
    const std::size_t b = text.find_first_not_of(" \t", colon + 1);
    const std::size_t e = text.find_last_not_of(" \t\r");
    std::string value = b == std::string::npos ? "" : text.substr(b, e - b + 1);
    if (value.size() >= 2 && (value[0] == '"' || value[0] == '\''))
      value = value.substr(1, value.size() - 2);
    const std::size_t kb = text.find_first_not_of(" \t");
    entries[text.substr(kb, colon - kb)] = {value, line};
  }
  return entries;
}

const YamlEntry& Require(const std::map<std::string, YamlEntry>& yaml, const std::string& key,
                         const std::string& path) {
  const auto it = yaml.find(key);
  if (it == yaml.end()) throw InputError(path, 0, key, "missing");
  return it->second;
}

std::string Directory(const std::string& path) {
  const std::size_t slash = path.rfind('/');
  return slash == std::string::npos ? "" : path.substr(0, slash + 1);
}

/// A binary PGM (P5, maxval < 256): header tokens with `#` comments, then width*height bytes.
struct Pgm {
  int width = 0, height = 0, maxval = 0;
  std::string pixels;
};
Pgm ReadPgm(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "", "cannot open file");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::size_t i = 0;
  auto token = [&](const char* field) {
    while (i < bytes.size() &&
           (std::isspace(static_cast<unsigned char>(bytes[i])) || bytes[i] == '#')) {
      if (bytes[i] == '#') i = bytes.find('\n', i);
      if (i == std::string::npos)
        i = bytes.size();
      else
        ++i;
    }
    const std::size_t b = i;
    while (i < bytes.size() && !std::isspace(static_cast<unsigned char>(bytes[i]))) ++i;
    if (b == i) throw InputError(path, 0, field, "truncated PGM header");
    return bytes.substr(b, i - b);
  };
  if (token("magic") != "P5") throw InputError(path, 1, "magic", "not a binary PGM (P5)");
  Pgm pgm;
  pgm.width = static_cast<int>(ParseNumber(token("width"), path, 0, "width"));
  pgm.height = static_cast<int>(ParseNumber(token("height"), path, 0, "height"));
  pgm.maxval = static_cast<int>(ParseNumber(token("maxval"), path, 0, "maxval"));
  if (pgm.width <= 0 || pgm.height <= 0 || pgm.maxval <= 0 || pgm.maxval > 255) {
    throw InputError(path, 0, "header", "unsupported size or maxval (8-bit P5 only)");
  }
  const std::size_t n = static_cast<std::size_t>(pgm.width) * static_cast<std::size_t>(pgm.height);
  if (bytes.size() < i + 1 + n)
    throw InputError(path, 0, "pixels", "fewer pixels than width*height");
  pgm.pixels = bytes.substr(i + 1, n);
  return pgm;
}

}  // namespace

OccupancyGrid ReadPgmMap(const std::string& yaml_path) {
  const auto yaml = ReadFlatYaml(yaml_path);
  auto number = [&](const std::string& key, double fallback) {
    const auto it = yaml.find(key);
    return it == yaml.end() ? fallback
                            : ParseNumber(it->second.value, yaml_path, it->second.line, key);
  };
  const auto mode = yaml.find("mode");
  if (mode != yaml.end() && mode->second.value != "trinary") {
    throw InputError(yaml_path, mode->second.line, "mode", "only 'trinary' maps are supported");
  }
  const YamlEntry& origin = Require(yaml, "origin", yaml_path);
  std::vector<double> xyz;
  {
    std::string list = origin.value;
    if (list.size() < 2 || list.front() != '[' || list.back() != ']') {
      throw InputError(yaml_path, origin.line, "origin", "expected [x, y, yaw]");
    }
    std::istringstream items(list.substr(1, list.size() - 2));
    for (std::string item; std::getline(items, item, ',');) {
      xyz.push_back(ParseNumber(item, yaml_path, origin.line, "origin"));
    }
    if (xyz.size() != 3) throw InputError(yaml_path, origin.line, "origin", "expected [x, y, yaw]");
    if (xyz[2] != 0.0)
      throw InputError(yaml_path, origin.line, "origin", "rotated maps unsupported");
  }
  OccupancyGrid grid;
  const YamlEntry& resolution = Require(yaml, "resolution", yaml_path);
  grid.resolution_m = ParseNumber(resolution.value, yaml_path, resolution.line, "resolution");
  if (grid.resolution_m <= 0.0)
    throw InputError(yaml_path, resolution.line, "resolution", "must be > 0");
  grid.origin_x_m = xyz[0];
  grid.origin_y_m = xyz[1];
  const bool negate = number("negate", 0.0) != 0.0;
  const double occupied_thresh = number("occupied_thresh", 0.65);
  const double free_thresh = number("free_thresh", 0.196);
  const YamlEntry& image = Require(yaml, "image", yaml_path);
  const std::string pgm_path =
      image.value.rfind('/', 0) == 0 ? image.value : Directory(yaml_path) + image.value;
  const Pgm pgm = ReadPgm(pgm_path);
  grid.width = pgm.width;
  grid.height = pgm.height;
  grid.p_occ.assign(pgm.pixels.size(), OccupancyGrid::kUnknown);
  for (int row = 0; row < grid.height; ++row) {
    for (int col = 0; col < grid.width; ++col) {
      const std::size_t k =
          static_cast<std::size_t>(grid.height - 1 - row) * static_cast<std::size_t>(grid.width) +
          static_cast<std::size_t>(col);
      const double v = static_cast<unsigned char>(pgm.pixels[k]) / static_cast<double>(pgm.maxval);
      const double p = negate ? v : 1.0 - v;  // map_server: dark = occupied
      if (p > occupied_thresh)
        grid.At(col, row) = 1.0f;
      else if (p < free_thresh)
        grid.At(col, row) = 0.0f;
    }
  }
  return grid;
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
  WriteFile(paths.pgm, pgm);
  WriteFile(paths.yaml, yaml);
  return paths;
}

}  // namespace lifelong::io
