#include "core/world/ros_map.hpp"

#include <yaml-cpp/yaml.h>

#include <charconv>
#include <cmath>
#include <stdexcept>

#include "core/io/atomic_file.hpp"

namespace irgs {
namespace {

namespace fs = std::filesystem;

// Pixels a saved map uses (the values ROS map_saver writes).
constexpr std::uint8_t kFreePixel = 254;
constexpr std::uint8_t kOccupiedPixel = 0;
constexpr std::uint8_t kUnknownPixel = 205;

class YamlReader {
 public:
  YamlReader(std::string source, std::vector<Diagnostic>& diagnostics)
      : source_(std::move(source)), diagnostics_(diagnostics) {}

  void error(const YAML::Mark& mark, std::string field, std::string message) {
    add(Severity::kError, mark, std::move(field), std::move(message));
  }
  void warning(const YAML::Mark& mark, std::string field, std::string message) {
    add(Severity::kWarning, mark, std::move(field), std::move(message));
  }

  // Required or optional scalar number; reports and returns nothing when invalid or missing
  // (missing is only an error when required).
  std::optional<double> number(const YAML::Node& map, const char* key, bool required) {
    const YAML::Node node = map[key];
    if (!node) {
      if (required)
        error(map.Mark(), key, std::string("missing required key '") + key + "'");
      return std::nullopt;
    }
    double value = 0.0;
    if (!node.IsScalar() || !YAML::convert<double>::decode(node, value)) {
      error(node.Mark(), key, "expected a number, found " + describe(node));
      return std::nullopt;
    }
    if (!std::isfinite(value)) {
      error(node.Mark(), key, "must be a finite number");
      return std::nullopt;
    }
    return value;
  }

  static std::string describe(const YAML::Node& node) {
    switch (node.Type()) {
      case YAML::NodeType::Null:
        return "nothing";
      case YAML::NodeType::Scalar:
        return "'" + node.Scalar() + "'";
      case YAML::NodeType::Sequence:
        return "a list";
      case YAML::NodeType::Map:
        return "a mapping";
      default:
        return "an undefined value";
    }
  }

 private:
  void add(Severity severity, const YAML::Mark& mark, std::string field, std::string message) {
    const bool known = !mark.is_null() && mark.line >= 0;
    diagnostics_.push_back({severity, source_, known ? mark.line + 1 : 0,
                            known ? mark.column + 1 : 0, std::move(field), std::move(message)});
  }

  std::string source_;
  std::vector<Diagnostic>& diagnostics_;
};

std::string formatNumber(double v) {
  char buffer[64];
  const auto r = std::to_chars(buffer, buffer + sizeof buffer, v);
  return std::string(buffer, r.ptr);
}

// Image file names are written plainly when safe, otherwise double-quoted with escapes.
std::string yamlString(const std::string& s) {
  bool plain = !s.empty();
  for (const char c : s) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '.' || c == '_' || c == '-' || c == '/';
    plain = plain && ok;
  }
  if (plain && s.front() != '-')
    return s;
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\')
      out += '\\';
    out += c;
  }
  return out + "\"";
}

std::optional<std::string> validateOptions(const RosMapSaveOptions& o) {
  if (!(std::isfinite(o.free_thresh) && std::isfinite(o.occupied_thresh) &&
        o.free_thresh > 1.0 / 255.0 && o.free_thresh < o.occupied_thresh &&
        o.occupied_thresh < 1.0)) {
    return "thresholds must satisfy 1/255 < free_thresh < occupied_thresh < 1 (got free " +
           formatNumber(o.free_thresh) + ", occupied " + formatNumber(o.occupied_thresh) + ")";
  }
  return std::nullopt;
}

}  // namespace

std::string_view toString(RosMapMode mode) {
  switch (mode) {
    case RosMapMode::kScale:
      return "scale";
    case RosMapMode::kRaw:
      return "raw";
    case RosMapMode::kTrinary:
      break;
  }
  return "trinary";
}

RasterMap rasterFromImage(const GrayImage& image, const RosMapMetadata& m) {
  RasterMap raster;
  raster.width = image.width;
  raster.height = image.height;
  raster.resolution_m = m.resolution_m;
  raster.origin = m.origin;
  raster.cells.assign(image.pixels.size(), RasterMap::kUnknown);

  // A lookup table per pixel value keeps the big maps fast.
  std::int8_t table[256];
  for (int p = 0; p < 256; ++p) {
    const double shade = p / 255.0;
    const double occ = m.negate ? shade : 1.0 - shade;
    std::int8_t value = RasterMap::kUnknown;
    switch (m.mode) {
      case RosMapMode::kTrinary:
      case RosMapMode::kScale:
        if (occ > m.occupied_thresh)
          value = RasterMap::kOccupied;
        else if (occ < m.free_thresh)
          value = RasterMap::kFree;
        else if (m.mode == RosMapMode::kScale)
          value = static_cast<std::int8_t>(
              std::rint((occ - m.free_thresh) / (m.occupied_thresh - m.free_thresh) * 100.0));
        break;
      case RosMapMode::kRaw:
        value = p <= 100 ? static_cast<std::int8_t>(p) : RasterMap::kUnknown;
        break;
    }
    table[p] = value;
  }
  const auto w = static_cast<std::size_t>(image.width);
  const auto h = static_cast<std::size_t>(image.height);
  for (std::size_t row = 0; row < h; ++row) {
    const std::uint8_t* src = image.pixels.data() + (h - 1 - row) * w;  // flip: image top first
    std::int8_t* dst = raster.cells.data() + row * w;
    for (std::size_t col = 0; col < w; ++col)
      dst[col] = table[src[col]];
  }
  return raster;
}

RosMapLoadResult parseRosMap(std::string_view yaml_text, const std::string& source_name,
                             const fs::path& base_dir) {
  RosMapLoadResult result;
  YamlReader reader(source_name, result.diagnostics);
  RosMapMetadata& meta = result.metadata;

  YAML::Node loaded;
  try {
    loaded = YAML::Load(std::string(yaml_text));
  } catch (const YAML::Exception& e) {
    reader.error(e.mark, {}, "YAML syntax error: " + e.msg);
    return result;
  }
  const YAML::Node doc = loaded;  // const: lookups of missing keys must not insert them
  if (!doc.IsMap()) {
    reader.error(doc.Mark(), {},
                 "expected a mapping of map_server keys (image, resolution, origin, ...), found " +
                     YamlReader::describe(doc));
    return result;
  }

  try {
    // image
    if (const YAML::Node node = doc["image"]; !node) {
      reader.error(doc.Mark(), "image", "missing required key 'image' (the PGM file name)");
    } else if (!node.IsScalar() || node.Scalar().empty()) {
      reader.error(node.Mark(), "image",
                   "expected an image file name, found " + YamlReader::describe(node));
    } else {
      meta.image = node.Scalar();
    }

    if (const auto v = reader.number(doc, "resolution", true)) {
      if (*v <= 0.0)
        reader.error(doc["resolution"].Mark(), "resolution",
                     "must be a positive number of metres per cell");
      else
        meta.resolution_m = *v;
    }

    if (const YAML::Node node = doc["origin"]; !node) {
      reader.error(doc.Mark(), "origin", "missing required key 'origin' ([x, y, yaw])");
    } else if (!node.IsSequence() || node.size() != 3) {
      reader.error(node.Mark(), "origin",
                   "expected a list of three numbers [x, y, yaw], found " +
                       (node.IsSequence() ? "a list of " + std::to_string(node.size())
                                          : YamlReader::describe(node)));
    } else {
      double xyz[3] = {0, 0, 0};
      bool ok = true;
      for (std::size_t i = 0; i < 3; ++i) {
        if (!node[i].IsScalar() || !YAML::convert<double>::decode(node[i], xyz[i]) ||
            !std::isfinite(xyz[i])) {
          reader.error(node[i].Mark(), "origin/" + std::to_string(i),
                       "expected a finite number, found " + YamlReader::describe(node[i]));
          ok = false;
        }
      }
      if (ok) {
        meta.origin = {xyz[0], xyz[1], xyz[2]};
        if (xyz[2] != 0.0)
          reader.warning(node.Mark(), "origin",
                         "a non-zero yaw is kept for saving but not applied (map_server ignores "
                         "it too)");
      }
    }

    if (const YAML::Node node = doc["negate"]; !node) {
      reader.warning(doc.Mark(), "negate", "missing key 'negate'; using 0");
    } else {
      int as_int = 0;
      bool as_bool = false;
      if (node.IsScalar() && YAML::convert<int>::decode(node, as_int) &&
          (as_int == 0 || as_int == 1))
        meta.negate = as_int == 1;
      else if (node.IsScalar() && YAML::convert<bool>::decode(node, as_bool))
        meta.negate = as_bool;
      else
        reader.error(node.Mark(), "negate", "expected 0 or 1, found " + YamlReader::describe(node));
    }

    for (const char* key : {"occupied_thresh", "free_thresh"}) {
      const bool occupied = key[0] == 'o';
      double& target = occupied ? meta.occupied_thresh : meta.free_thresh;
      if (!doc[key]) {
        reader.warning(doc.Mark(), key,
                       std::string("missing key '") + key + "'; using " + formatNumber(target));
      } else if (const auto v = reader.number(doc, key, true)) {
        if (*v < 0.0 || *v > 1.0)
          reader.error(doc[key].Mark(), key, "must lie between 0 and 1");
        else
          target = *v;
      }
    }
    if (!hasErrors(result.diagnostics) && meta.free_thresh >= meta.occupied_thresh) {
      reader.error(
          doc["free_thresh"].Mark(), "free_thresh",
          "must be smaller than occupied_thresh (" + formatNumber(meta.occupied_thresh) + ")");
    }

    if (const YAML::Node node = doc["mode"]; node) {
      const std::string mode = node.IsScalar() ? node.Scalar() : std::string();
      if (mode == "trinary")
        meta.mode = RosMapMode::kTrinary;
      else if (mode == "scale")
        meta.mode = RosMapMode::kScale;
      else if (mode == "raw")
        meta.mode = RosMapMode::kRaw;
      else
        reader.error(node.Mark(), "mode",
                     "expected trinary, scale or raw, found " + YamlReader::describe(node));
    }
  } catch (const YAML::Exception& e) {
    reader.error(e.mark, {}, "cannot read the map description: " + e.msg);
  }
  if (hasErrors(result.diagnostics))
    return result;

  fs::path image_path = meta.image;
  if (image_path.is_relative())
    image_path = base_dir / image_path;
  PgmReadResult image = readPgmFile(image_path);
  if (!image.image) {
    reader.error(doc["image"].Mark(), "image",
                 "cannot load the image '" + meta.image + "' (IRGS reads PGM images: P5 or P2)");
    for (Diagnostic& d : image.diagnostics)
      result.diagnostics.push_back(std::move(d));
    return result;
  }
  result.raster = rasterFromImage(*image.image, meta);
  return result;
}

RosMapLoadResult loadRosMap(const fs::path& yaml_path) {
  const ReadFileResult file = readFile(yaml_path);
  if (!file.ok()) {
    RosMapLoadResult result;
    result.diagnostics.push_back({Severity::kError, yaml_path.string(), 0, 0, {}, file.error});
    return result;
  }
  return parseRosMap(file.bytes, yaml_path.string(), yaml_path.parent_path());
}

GrayImage imageFromRaster(const RasterMap& raster, const RosMapSaveOptions& o) {
  if (raster.empty())
    throw std::invalid_argument("imageFromRaster: the raster is empty");
  const auto w = static_cast<std::size_t>(raster.width);
  const auto h = static_cast<std::size_t>(raster.height);
  if (raster.cells.size() != w * h)
    throw std::invalid_argument("imageFromRaster: cell count does not match width * height");

  // Pixel for an occupancy probability occ, before negation.
  const auto pixelForOcc = [](double occ) {
    return static_cast<std::uint8_t>(std::clamp(std::rint(255.0 * (1.0 - occ)), 0.0, 255.0));
  };
  // 205 reads back as unknown only if its occupancy lies between the thresholds.
  const double occ205 = 1.0 - kUnknownPixel / 255.0;
  const std::uint8_t unknown = occ205 >= o.free_thresh && occ205 <= o.occupied_thresh
                                   ? kUnknownPixel
                                   : pixelForOcc(0.5 * (o.free_thresh + o.occupied_thresh));
  const auto free_int = static_cast<int>(std::rint(o.free_thresh * 100.0));
  const auto occupied_int = static_cast<int>(std::rint(o.occupied_thresh * 100.0));

  std::uint8_t table[256];  // indexed by cell value + 128
  for (int value = -128; value < 128; ++value) {
    std::uint8_t pixel = unknown;
    const bool known = value >= 0 && value <= 100;
    switch (o.mode) {
      case RosMapMode::kTrinary:
        if (known && value <= free_int)
          pixel = kFreePixel;
        else if (known && value >= occupied_int)
          pixel = kOccupiedPixel;
        break;
      case RosMapMode::kScale:
        if (value == 0)
          pixel = 255;
        else if (value == 100)
          pixel = 0;
        else if (known)
          pixel = pixelForOcc(o.free_thresh + value / 100.0 * (o.occupied_thresh - o.free_thresh));
        break;
      case RosMapMode::kRaw:
        pixel = known ? static_cast<std::uint8_t>(value) : 255;
        break;
    }
    if (o.negate && o.mode != RosMapMode::kRaw)
      pixel = static_cast<std::uint8_t>(255 - pixel);
    table[value + 128] = pixel;
  }

  GrayImage image;
  image.width = raster.width;
  image.height = raster.height;
  image.pixels.resize(w * h);
  for (std::size_t row = 0; row < h; ++row) {
    const std::int8_t* src = raster.cells.data() + row * w;
    std::uint8_t* dst = image.pixels.data() + (h - 1 - row) * w;
    for (std::size_t col = 0; col < w; ++col)
      dst[col] = table[src[col] + 128];
  }
  return image;
}

std::optional<std::string> saveRosMap(const RasterMap& raster, const fs::path& yaml_path,
                                      const RosMapSaveOptions& options) {
  if (raster.empty() || raster.cells.size() != static_cast<std::size_t>(raster.width) *
                                                   static_cast<std::size_t>(raster.height))
    return "cannot save " + yaml_path.string() + ": the raster is empty or inconsistent";
  if (!(std::isfinite(raster.resolution_m) && raster.resolution_m > 0.0))
    return "cannot save " + yaml_path.string() + ": resolution must be positive";
  if (!(std::isfinite(raster.origin.x) && std::isfinite(raster.origin.y) &&
        std::isfinite(raster.origin.theta)))
    return "cannot save " + yaml_path.string() + ": origin must be finite";
  if (options.mode != RosMapMode::kRaw) {
    if (auto error = validateOptions(options))
      return "cannot save " + yaml_path.string() + ": " + *error;
  }
  fs::path image_path = yaml_path;
  image_path.replace_extension(".pgm");
  if (image_path == yaml_path)
    return "cannot save " + yaml_path.string() + ": the YAML file needs its own name, not .pgm";

  const GrayImage image = imageFromRaster(raster, options);
  if (auto error = writePgmFile(image, image_path, "written by IRGS"))
    return error;

  const bool negate = options.negate && options.mode != RosMapMode::kRaw;
  std::string yaml;
  yaml += "image: " + yamlString(image_path.filename().string()) + "\n";
  yaml += "mode: " + std::string(toString(options.mode)) + "\n";
  yaml += "resolution: " + formatNumber(raster.resolution_m) + "\n";
  yaml += "origin: [" + formatNumber(raster.origin.x) + ", " + formatNumber(raster.origin.y) +
          ", " + formatNumber(raster.origin.theta) + "]\n";
  yaml += std::string("negate: ") + (negate ? "1" : "0") + "\n";
  yaml += "occupied_thresh: " + formatNumber(options.occupied_thresh) + "\n";
  yaml += "free_thresh: " + formatNumber(options.free_thresh) + "\n";
  return writeFileAtomically(yaml_path, yaml);
}

}  // namespace irgs
