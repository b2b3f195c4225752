#include "core/robot/robot_profile_file.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <set>

#include "core/io/atomic_file.hpp"
#include "core/io/json_locator.hpp"

namespace irgs {

namespace {

using Json = nlohmann::json;

constexpr int kFormatVersion = 1;
constexpr std::size_t kMaxBumpers = 32;  // TelemetrySample::bumpers is a 32-bit mask
constexpr double kBumperOnOutlineTolerance_m = 0.01;
// A profile nests four levels deep; anything far deeper is not a profile, and refusing it up
// front keeps the parser and the position scan cheap on hostile input.
constexpr int kMaxNesting = 64;

// 1-based line and column of byte `offset` (columns in bytes).
TextPosition positionOfByte(std::string_view text, std::size_t offset) {
  offset = std::min(offset, text.size());
  TextPosition pos{1, 1};
  for (std::size_t i = 0; i < offset; ++i) {
    if (text[i] == '\n') {
      ++pos.line;
      pos.column = 1;
    } else {
      ++pos.column;
    }
  }
  return pos;
}

// Collects diagnostics for one document, locating fields through the scanned positions.
class Reader {
 public:
  Reader(std::string file, std::string_view text, std::vector<Diagnostic>& out)
      : file_(std::move(file)), positions_(text), out_(out) {}

  void error(const std::string& field, std::string message) {
    add(Severity::kError, field, std::move(message));
  }
  void warning(const std::string& field, std::string message) {
    add(Severity::kWarning, field, std::move(message));
  }

  // Keeps unknown keys of `object` in `extra`, warning about each one.
  void keepUnknown(const Json& object, const std::string& pointer,
                   const std::set<std::string>& known, Json& extra,
                   const std::set<std::string>& silent = {}) {
    for (auto it = object.begin(); it != object.end(); ++it) {
      if (known.count(it.key()))
        continue;
      extra[it.key()] = it.value();
      if (!silent.count(it.key()))
        warning(pointer + "/" + JsonLocator::escapeToken(it.key()), "unknown key (kept as is)");
    }
  }

  // A number field. Missing: error when required, otherwise `fallback`.
  std::optional<double> number(const Json& object, const std::string& pointer, const char* key,
                               bool required) {
    const std::string field = pointer + "/" + key;
    const auto it = object.find(key);
    if (it == object.end()) {
      if (required)
        error(field, "required number is missing");
      return std::nullopt;
    }
    if (!it->is_number()) {
      error(field, std::string("expected a number, found ") + it->type_name());
      return std::nullopt;
    }
    const double v = it->get<double>();
    if (!std::isfinite(v)) {
      error(field, "expected a finite number");
      return std::nullopt;
    }
    return v;
  }

  // Reads an optional/required number into `target`, checking `valid` (message `expected`).
  void read(const Json& object, const std::string& pointer, const char* key, double& target,
            bool required, const std::function<bool(double)>& valid, const char* expected,
            double scale = 1.0) {
    if (const auto v = number(object, pointer, key, required)) {
      if (!valid(*v)) {
        error(pointer + "/" + key,
              "value " + formatNumber(*v) + " out of range: expected " + expected);
        return;
      }
      target = *v * scale;
    }
  }

  std::optional<std::string> string(const Json& object, const std::string& pointer, const char* key,
                                    bool required) {
    const auto it = object.find(key);
    if (it == object.end()) {
      if (required)
        error(pointer + "/" + key, "required string is missing");
      return std::nullopt;
    }
    if (!it->is_string()) {
      error(pointer + "/" + key, std::string("expected a string, found ") + it->type_name());
      return std::nullopt;
    }
    return it->get<std::string>();
  }

  static std::string formatNumber(double v) {
    std::string s = Json(v).dump();
    return s;
  }

 private:
  void add(Severity severity, const std::string& field, std::string message) {
    const TextPosition pos = positions_.locate(field);
    out_.push_back({severity, file_, pos.line, pos.column, field, std::move(message)});
  }

  std::string file_;
  JsonLocator positions_;
  std::vector<Diagnostic>& out_;
};

bool positive(double v) {
  return v > 0.0;
}
bool nonNegative(double v) {
  return v >= 0.0;
}

const std::set<std::string> kTopKeys = {"format_version", "name",      "description",  "notes",
                                        "drive",          "limits",    "body_outline", "sonars",
                                        "bumpers",        "proximity", "calibration",  "arcos",
                                        "ceiling_camera"};

// Signed area (shoelace), > 0 for counter-clockwise.
double signedArea(const std::vector<Vec2>& poly) {
  double twice = 0.0;
  for (std::size_t i = 0; i < poly.size(); ++i)
    twice += cross(poly[i], poly[(i + 1) % poly.size()]);
  return 0.5 * twice;
}

bool properlyCross(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const double d1 = cross(b - a, c - a), d2 = cross(b - a, d - a);
  const double d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
  return ((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0));
}

double distanceToSegment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

void readDrive(Reader& r, const Json& root, RobotProfile& profile) {
  const std::string ptr = "/drive";
  const auto it = root.find("drive");
  if (it == root.end()) {
    r.error(ptr, "required object is missing");
    return;
  }
  if (!it->is_object()) {
    r.error(ptr, "expected an object");
    return;
  }
  const Json& o = *it;
  DriveGeometry& d = profile.drive;
  if (const auto type = r.string(o, ptr, "type", false)) {
    if (*type == "differential")
      d.type = DriveType::kDifferential;
    else if (*type == "three_caster")
      d.type = DriveType::kThreeCaster;
    else if (*type == "mouse_sensor")
      d.type = DriveType::kMouseSensor;
    else
      r.error(ptr + "/type", "unknown drive type \"" + *type +
                                 "\": expected differential, three_caster or mouse_sensor");
  }
  r.read(o, ptr, "wheel_radius_m", d.wheel_radius_m, true, positive, "> 0");
  r.read(o, ptr, "wheelbase_m", d.wheelbase_m, true, positive, "> 0");
  r.read(o, ptr, "encoder_counts_per_motor_rad", d.encoder_counts_per_motor_rad, false, positive,
         "> 0");
  r.read(o, ptr, "gear_ratio", d.gear_ratio, false, positive, "> 0");
  // The drive-type sections are read (and checked) where they are used: "three_caster" by
  // core/estimation/caster_profile, "mouse_sensors" by core/estimation/mouse_odometry;
  // "castor_offset_m" is the Type (2,0) robot's castor offset d of 004_…. Kept in `extra`
  // without a warning.
  r.keepUnknown(
      o, ptr,
      {"type", "wheel_radius_m", "wheelbase_m", "encoder_counts_per_motor_rad", "gear_ratio"},
      d.extra, {"three_caster", "mouse_sensors", "castor_offset_m"});
}

void readLimits(Reader& r, const Json& root, RobotProfile& profile) {
  const std::string ptr = "/limits";
  const auto it = root.find("limits");
  if (it == root.end())
    return;
  if (!it->is_object()) {
    r.error(ptr, "expected an object");
    return;
  }
  const Json& o = *it;
  MotionLimits& l = profile.limits;
  r.read(o, ptr, "max_speed_mps", l.max_speed_mps, false, positive, "> 0");
  r.read(o, ptr, "max_turn_rate_degps", l.max_turn_rate_radps, false, positive, "> 0",
         degToRad(1.0));
  r.read(o, ptr, "max_accel_mps2", l.max_accel_mps2, false, positive, "> 0");
  r.read(o, ptr, "max_turn_accel_degps2", l.max_turn_accel_radps2, false, positive, "> 0",
         degToRad(1.0));
  r.keepUnknown(o, ptr,
                {"max_speed_mps", "max_turn_rate_degps", "max_accel_mps2", "max_turn_accel_degps2"},
                l.extra);
}

void readOutline(Reader& r, const Json& root, RobotProfile& profile) {
  const std::string ptr = "/body_outline";
  const auto it = root.find("body_outline");
  if (it == root.end()) {
    r.error(ptr, "required array of [x, y] points is missing");
    return;
  }
  if (!it->is_array()) {
    r.error(ptr, "expected an array of [x, y] points");
    return;
  }
  std::vector<Vec2> poly;
  bool ok = true;
  for (std::size_t i = 0; i < it->size(); ++i) {
    const Json& p = (*it)[i];
    const std::string field = ptr + "/" + std::to_string(i);
    if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number() ||
        !std::isfinite(p[0].get<double>()) || !std::isfinite(p[1].get<double>())) {
      r.error(field, "expected a point [x_m, y_m] of two finite numbers");
      ok = false;
      continue;
    }
    poly.emplace_back(p[0].get<double>(), p[1].get<double>());
  }
  if (!ok)
    return;
  if (poly.size() < 3) {
    r.error(ptr, "a body outline needs at least 3 points, found " + std::to_string(poly.size()));
    return;
  }
  const std::size_t n = poly.size();
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      if (j == i + 1 || (i == 0 && j == n - 1))
        continue;  // neighbouring edges share a vertex
      if (properlyCross(poly[i], poly[(i + 1) % n], poly[j], poly[(j + 1) % n])) {
        r.error(ptr, "the outline crosses itself (edges " + std::to_string(i) + " and " +
                         std::to_string(j) + ")");
        return;
      }
    }
  }
  const double area = signedArea(poly);
  if (std::abs(area) < 1e-6) {
    r.error(ptr, "the outline encloses no area");
    return;
  }
  if (area < 0.0)
    std::reverse(poly.begin(), poly.end());
  profile.body_outline = std::move(poly);
}

// Calls `each(object, pointer, index)` for every element of the array `key`, if present.
void forEachItem(Reader& r, const Json& root, const char* key,
                 const std::function<void(const Json&, const std::string&, std::size_t)>& each) {
  const auto it = root.find(key);
  const std::string ptr = std::string("/") + key;
  if (it == root.end())
    return;
  if (!it->is_array()) {
    r.error(ptr, "expected an array of objects");
    return;
  }
  for (std::size_t i = 0; i < it->size(); ++i) {
    const std::string item_ptr = ptr + "/" + std::to_string(i);
    if (!(*it)[i].is_object()) {
      r.error(item_ptr, "expected an object");
      continue;
    }
    each((*it)[i], item_ptr, i);
  }
}

void readPosition(Reader& r, const Json& o, const std::string& ptr, Vec2& position) {
  double x = position.x(), y = position.y();
  r.read(
      o, ptr, "x_m", x, true, [](double) { return true; }, "a number");
  r.read(
      o, ptr, "y_m", y, true, [](double) { return true; }, "a number");
  position = {x, y};
}

// A sensor mount: x_m, y_m and heading_deg in the body frame.
Pose2 readMount(Reader& r, const Json& o, const std::string& ptr) {
  Vec2 p = Vec2::Zero();
  readPosition(r, o, ptr, p);
  double heading = 0.0;
  r.read(
      o, ptr, "heading_deg", heading, true, [](double) { return true; }, "a number");
  return {p.x(), p.y(), wrapAngle(degToRad(heading))};
}

std::string nameOr(Reader& r, const Json& o, const std::string& ptr, const std::string& fallback) {
  return r.string(o, ptr, "name", false).value_or(fallback);
}

void readSonars(Reader& r, const Json& root, RobotProfile& profile) {
  forEachItem(r, root, "sonars", [&](const Json& o, const std::string& ptr, std::size_t i) {
    SonarSpec s;
    s.name = nameOr(r, o, ptr, "sonar_" + std::to_string(i));
    s.mount = readMount(r, o, ptr);
    r.read(
        o, ptr, "beam_width_deg", s.beam_width_rad, false,
        [](double v) { return v > 0.0 && v <= 180.0; }, "(0, 180] degrees", degToRad(1.0));
    r.read(o, ptr, "min_range_m", s.min_range_m, false, nonNegative, ">= 0");
    r.read(o, ptr, "max_range_m", s.max_range_m, false, positive, "> 0");
    r.read(o, ptr, "rate_hz", s.rate_hz, false, positive, "> 0");
    if (s.max_range_m <= s.min_range_m)
      r.error(ptr + "/max_range_m", "max_range_m must be greater than min_range_m");
    r.keepUnknown(o, ptr,
                  {"name", "x_m", "y_m", "heading_deg", "beam_width_deg", "min_range_m",
                   "max_range_m", "rate_hz"},
                  s.extra);
    profile.sonars.push_back(std::move(s));
  });
}

void readBumpers(Reader& r, const Json& root, RobotProfile& profile) {
  forEachItem(r, root, "bumpers", [&](const Json& o, const std::string& ptr, std::size_t i) {
    BumperSpec b;
    b.name = nameOr(r, o, ptr, "bumper_" + std::to_string(i));
    readPosition(r, o, ptr, b.position);
    double normal = 0.0;
    r.read(
        o, ptr, "normal_deg", normal, true, [](double) { return true; }, "a number");
    b.normal_rad = wrapAngle(degToRad(normal));
    r.read(o, ptr, "half_width_m", b.half_width_m, false, nonNegative, ">= 0");
    r.keepUnknown(o, ptr, {"name", "x_m", "y_m", "normal_deg", "half_width_m"}, b.extra);
    profile.bumpers.push_back(std::move(b));
  });
  if (profile.bumpers.size() > kMaxBumpers)
    r.error("/bumpers", "at most " + std::to_string(kMaxBumpers) +
                            " bumpers are supported, found " +
                            std::to_string(profile.bumpers.size()));
}

void readProximity(Reader& r, const Json& root, RobotProfile& profile) {
  forEachItem(r, root, "proximity", [&](const Json& o, const std::string& ptr, std::size_t i) {
    ProximitySpec s;
    s.name = nameOr(r, o, ptr, "proximity_" + std::to_string(i));
    s.mount = readMount(r, o, ptr);
    r.read(o, ptr, "max_range_m", s.max_range_m, false, positive, "> 0");
    r.read(o, ptr, "rate_hz", s.rate_hz, false, positive, "> 0");
    r.keepUnknown(o, ptr, {"name", "x_m", "y_m", "heading_deg", "max_range_m", "rate_hz"}, s.extra);
    profile.proximity.push_back(std::move(s));
  });
}

// Checks that need the whole profile: bumpers on the outline, unique sensor names.
void crossChecks(Reader& r, const RobotProfile& profile) {
  const auto& poly = profile.body_outline;
  if (poly.size() >= 3) {
    for (std::size_t i = 0; i < profile.bumpers.size(); ++i) {
      double d = std::numeric_limits<double>::infinity();
      for (std::size_t k = 0; k < poly.size(); ++k)
        d = std::min(d, distanceToSegment(profile.bumpers[i].position, poly[k],
                                          poly[(k + 1) % poly.size()]));
      if (d > kBumperOnOutlineTolerance_m)
        r.warning("/bumpers/" + std::to_string(i),
                  "bumper is " + Reader::formatNumber(std::round(d * 1000.0) / 1000.0) +
                      " m from the body outline; bumpers sense only at the outline");
    }
  }
  auto unique = [&](const char* key, const std::vector<std::string>& names) {
    std::set<std::string> seen;
    for (std::size_t i = 0; i < names.size(); ++i) {
      if (!seen.insert(names[i]).second)
        r.warning(std::string("/") + key + "/" + std::to_string(i) + "/name",
                  "duplicate name \"" + names[i] + "\"");
    }
  };
  std::vector<std::string> names;
  for (const auto& s : profile.sonars)
    names.push_back(s.name);
  unique("sonars", names);
  names.clear();
  for (const auto& s : profile.bumpers)
    names.push_back(s.name);
  unique("bumpers", names);
  names.clear();
  for (const auto& s : profile.proximity)
    names.push_back(s.name);
  unique("proximity", names);
}

// "[json.exception.parse_error.101] parse error at line 3, column 5: syntax error ..." ->
// "syntax error ...": the location goes into the diagnostic's line and column instead.
std::string parseErrorMessage(const std::string& what) {
  const std::size_t at = what.find("parse error");
  std::string msg = at == std::string::npos ? what : what.substr(at);
  if (!msg.empty() && msg.front() == '[') {  // "[json.exception.out_of_range.406] number ..."
    if (const std::size_t close = msg.find("] "); close != std::string::npos)
      return msg.substr(close + 2);
  }
  if (const std::size_t colon = msg.find(": "); colon != std::string::npos)
    msg = msg.substr(colon + 2);
  return msg;
}

// Rounds a converted angle so files do not show 89.99999999999999.
double tidyDegrees(double rad) {
  return std::round(radToDeg(rad) * 1e9) / 1e9;
}

nlohmann::ordered_json withExtra(nlohmann::ordered_json object, const Json& extra) {
  if (extra.is_object()) {
    for (auto it = extra.begin(); it != extra.end(); ++it) {
      if (!object.contains(it.key()))
        object[it.key()] = nlohmann::ordered_json::parse(it.value().dump());
    }
  }
  return object;
}

}  // namespace

RobotProfileResult parseRobotProfileJson(std::string_view text, const std::string& source_name) {
  RobotProfileResult result;
  if (const NestingDepth nesting = maxNestingDepth(text); nesting.depth > kMaxNesting) {
    const TextPosition pos = positionOfByte(text, nesting.offset);
    result.diagnostics.push_back({Severity::kError, source_name, pos.line, pos.column, "",
                                  "JSON nested more than " + std::to_string(kMaxNesting) +
                                      " levels deep: not a robot profile"});
    return result;
  }
  Json root;
  try {
    root = Json::parse(text.begin(), text.end());
  } catch (const Json::parse_error& e) {
    // e.byte is the 1-based index of the last character read.
    const TextPosition pos = positionOfByte(text, e.byte > 0 ? e.byte - 1 : 0);
    result.diagnostics.push_back({Severity::kError, source_name, pos.line, pos.column, "",
                                  "invalid JSON: " + parseErrorMessage(e.what())});
    return result;
  } catch (const Json::exception& e) {
    // Not a syntax error but unrepresentable content, e.g. a number overflowing a double.
    result.diagnostics.push_back(
        {Severity::kError, source_name, 0, 0, "", "invalid JSON: " + parseErrorMessage(e.what())});
    return result;
  }
  Reader r(source_name, text, result.diagnostics);
  if (!root.is_object()) {
    r.error("", std::string("expected a JSON object at the top level, found ") + root.type_name());
    return result;
  }
  RobotProfile profile;
  if (const auto it = root.find("format_version"); it != root.end()) {
    if (!it->is_number_integer() || it->get<std::int64_t>() != kFormatVersion) {
      r.error("/format_version", "unsupported format_version " + it->dump() + ": expected " +
                                     std::to_string(kFormatVersion));
      return result;
    }
  }
  if (const auto name = r.string(root, "", "name", true))
    profile.name = *name;
  if (const auto description = r.string(root, "", "description", false))
    profile.description = *description;
  readDrive(r, root, profile);
  readLimits(r, root, profile);
  readOutline(r, root, profile);
  readSonars(r, root, profile);
  readBumpers(r, root, profile);
  readProximity(r, root, profile);
  r.keepUnknown(root, "", kTopKeys, profile.extra);
  if (const auto it = root.find("notes"); it != root.end())
    profile.extra["notes"] = *it;  // documented free text: kept without a warning
  // Documented calibration results (core/calibration/profile_calibration.hpp): kept as is,
  // written back by robotProfileToJson through `extra`, read by the calibration code.
  if (const auto it = root.find("calibration"); it != root.end())
    profile.extra["calibration"] = *it;
  // ARCOS conversion factors of Pioneer-class robots (comms/robot/arcos_params.hpp reads and
  // checks them): kept as is, without a warning.
  if (const auto it = root.find("arcos"); it != root.end())
    profile.extra["arcos"] = *it;
  // The ceiling camera of 002_… (core/camera/ceiling_camera_config.hpp reads and checks it).
  if (const auto it = root.find("ceiling_camera"); it != root.end())
    profile.extra["ceiling_camera"] = *it;
  crossChecks(r, profile);
  if (!hasErrors(result.diagnostics))
    result.profile = std::move(profile);
  return result;
}

RobotProfileResult loadRobotProfileFile(const std::filesystem::path& path) {
  const ReadFileResult file = readFile(path);
  if (!file.ok()) {
    RobotProfileResult result;
    result.diagnostics.push_back({Severity::kError, path.string(), 0, 0, "", file.error});
    return result;
  }
  return parseRobotProfileJson(file.bytes, path.string());
}

nlohmann::ordered_json robotProfileToJson(const RobotProfile& profile) {
  using OJson = nlohmann::ordered_json;
  OJson out;
  out["format_version"] = kFormatVersion;
  out["name"] = profile.name;
  if (!profile.description.empty())
    out["description"] = profile.description;
  if (profile.extra.contains("notes"))
    out["notes"] = OJson::parse(profile.extra["notes"].dump());

  const DriveGeometry& d = profile.drive;
  const char* type = d.type == DriveType::kDifferential  ? "differential"
                     : d.type == DriveType::kThreeCaster ? "three_caster"
                                                         : "mouse_sensor";
  out["drive"] = withExtra({{"type", type},
                            {"wheel_radius_m", d.wheel_radius_m},
                            {"wheelbase_m", d.wheelbase_m},
                            {"encoder_counts_per_motor_rad", d.encoder_counts_per_motor_rad},
                            {"gear_ratio", d.gear_ratio}},
                           d.extra);
  const MotionLimits& l = profile.limits;
  out["limits"] = withExtra({{"max_speed_mps", l.max_speed_mps},
                             {"max_turn_rate_degps", tidyDegrees(l.max_turn_rate_radps)},
                             {"max_accel_mps2", l.max_accel_mps2},
                             {"max_turn_accel_degps2", tidyDegrees(l.max_turn_accel_radps2)}},
                            l.extra);
  OJson outline = OJson::array();
  for (const Vec2& p : profile.body_outline)
    outline.push_back({p.x(), p.y()});
  out["body_outline"] = outline;

  OJson sonars = OJson::array();
  for (const SonarSpec& s : profile.sonars) {
    sonars.push_back(withExtra({{"name", s.name},
                                {"x_m", s.mount.x},
                                {"y_m", s.mount.y},
                                {"heading_deg", tidyDegrees(s.mount.theta)},
                                {"beam_width_deg", tidyDegrees(s.beam_width_rad)},
                                {"min_range_m", s.min_range_m},
                                {"max_range_m", s.max_range_m},
                                {"rate_hz", s.rate_hz}},
                               s.extra));
  }
  out["sonars"] = sonars;
  OJson bumpers = OJson::array();
  for (const BumperSpec& b : profile.bumpers) {
    bumpers.push_back(withExtra({{"name", b.name},
                                 {"x_m", b.position.x()},
                                 {"y_m", b.position.y()},
                                 {"normal_deg", tidyDegrees(b.normal_rad)},
                                 {"half_width_m", b.half_width_m}},
                                b.extra));
  }
  out["bumpers"] = bumpers;
  OJson proximity = OJson::array();
  for (const ProximitySpec& s : profile.proximity) {
    proximity.push_back(withExtra({{"name", s.name},
                                   {"x_m", s.mount.x},
                                   {"y_m", s.mount.y},
                                   {"heading_deg", tidyDegrees(s.mount.theta)},
                                   {"max_range_m", s.max_range_m},
                                   {"rate_hz", s.rate_hz}},
                                  s.extra));
  }
  out["proximity"] = proximity;
  return withExtra(std::move(out), profile.extra);
}

std::string formatRobotProfileJson(const RobotProfile& profile) {
  return robotProfileToJson(profile).dump(2) + "\n";
}

std::optional<Diagnostic> saveRobotProfileFile(const RobotProfile& profile,
                                               const std::filesystem::path& path) {
  if (const auto error = writeFileAtomically(path, formatRobotProfileJson(profile)))
    return Diagnostic{Severity::kError, path.string(), 0, 0, "", *error};
  return std::nullopt;
}

}  // namespace irgs
