#include "core/sim/drive_script.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>

#include "core/geometry/types.hpp"
#include "core/io/atomic_file.hpp"

namespace irgs {

DriveScript::DriveScript(std::vector<DriveScriptStep> steps) : steps_(std::move(steps)) {
  for (std::size_t i = 0; i < steps_.size(); ++i) {
    const double t = steps_[i].time_s;
    if (!std::isfinite(t) || t < 0.0)
      throw std::invalid_argument("DriveScript: times must be finite and >= 0");
    if (i > 0 && t < steps_[i - 1].time_s)
      throw std::invalid_argument("DriveScript: times must not decrease");
  }
}

VelocityCommand DriveScript::commandAt(double t_s) const {
  // First step strictly later than t; the one before it is in force.
  const auto it =
      std::upper_bound(steps_.begin(), steps_.end(), t_s,
                       [](double t, const DriveScriptStep& step) { return t < step.time_s; });
  if (it == steps_.begin())
    return {};
  return std::prev(it)->command;
}

namespace {

struct Token {
  std::string_view text;
  int column = 0;  // 1-based
};

std::vector<Token> tokenize(std::string_view line) {
  std::vector<Token> tokens;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t'))
      ++i;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t')
      ++i;
    if (i > start)
      tokens.push_back({line.substr(start, i - start), static_cast<int>(start) + 1});
  }
  return tokens;
}

std::optional<double> parseNumber(std::string_view text) {
  double value = 0.0;
  const char* first = text.data();
  const char* last = text.data() + text.size();
  if (!text.empty() && text.front() == '+')
    ++first;  // from_chars does not accept a leading '+'
  const auto [ptr, ec] = std::from_chars(first, last, value);
  if (ec != std::errc() || ptr != last || !std::isfinite(value))
    return std::nullopt;
  return value;
}

}  // namespace

DriveScriptResult parseDriveScript(std::string_view text, const std::string& source_name) {
  DriveScriptResult result;
  auto error = [&](int line, int column, std::string message) {
    result.diagnostics.push_back(
        {Severity::kError, source_name, line, column, "", std::move(message)});
  };
  std::vector<DriveScriptStep> steps;
  double previous_time = 0.0;
  int line_number = 0;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    const std::size_t end = std::min(text.find('\n', pos), text.size());
    std::string_view line = text.substr(pos, end - pos);
    pos = end + 1;
    ++line_number;
    if (const std::size_t hash = line.find('#'); hash != std::string_view::npos)
      line = line.substr(0, hash);
    if (!line.empty() && line.back() == '\r')
      line.remove_suffix(1);
    const std::vector<Token> tokens = tokenize(line);
    if (tokens.empty())
      continue;

    const auto time = parseNumber(tokens[0].text);
    if (!time) {
      error(line_number, tokens[0].column,
            "expected a time in seconds, found \"" + std::string(tokens[0].text) + "\"");
      continue;
    }
    if (*time < 0.0) {
      error(line_number, tokens[0].column, "time must be >= 0");
      continue;
    }
    if (!steps.empty() && *time < previous_time) {
      error(line_number, tokens[0].column,
            "time " + std::string(tokens[0].text) + " is earlier than the previous line's");
      continue;
    }
    if (tokens.size() < 2) {
      error(line_number, tokens[0].column + static_cast<int>(tokens[0].text.size()),
            "expected a command after the time: drive V_MPS OMEGA_DEGPS, or stop");
      continue;
    }
    const Token& command = tokens[1];
    DriveScriptStep step;
    step.time_s = *time;
    step.line = line_number;
    if (command.text == "stop") {
      if (tokens.size() > 2) {
        error(line_number, tokens[2].column, "stop takes no arguments");
        continue;
      }
    } else if (command.text == "drive") {
      if (tokens.size() != 4) {
        error(line_number,
              tokens.size() > 4 ? tokens[4].column
                                : command.column + static_cast<int>(command.text.size()),
              "drive takes two numbers: V_MPS OMEGA_DEGPS");
        continue;
      }
      const auto v = parseNumber(tokens[2].text);
      const auto w = parseNumber(tokens[3].text);
      if (!v) {
        error(line_number, tokens[2].column,
              "expected a speed in m/s, found \"" + std::string(tokens[2].text) + "\"");
        continue;
      }
      if (!w) {
        error(line_number, tokens[3].column,
              "expected a turn rate in deg/s, found \"" + std::string(tokens[3].text) + "\"");
        continue;
      }
      step.command = {*v, degToRad(*w)};
    } else {
      error(line_number, command.column,
            "unknown command \"" + std::string(command.text) + "\": expected drive or stop");
      continue;
    }
    previous_time = *time;
    steps.push_back(step);
  }
  if (!hasErrors(result.diagnostics))
    result.script = DriveScript(std::move(steps));
  return result;
}

DriveScriptResult loadDriveScriptFile(const std::filesystem::path& path) {
  const ReadFileResult file = readFile(path);
  if (!file.ok()) {
    DriveScriptResult result;
    result.diagnostics.push_back({Severity::kError, path.string(), 0, 0, "", file.error});
    return result;
  }
  return parseDriveScript(file.bytes, path.string());
}

}  // namespace irgs
