#include "core/estimation/gyro_calibration.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <charconv>
#include <cmath>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "core/geometry/types.hpp"

namespace irgs {

namespace {

struct PolyFit {
  bool ok = false;
  std::vector<double> coefficients;  // c_0 .. c_order, in the unscaled variable
  double rms = 0.0;
  std::string problem;
};

// Least squares y = sum_j c_j u^j, j = 0..order. The variable is scaled by its largest magnitude
// so the Vandermonde columns are of similar size; column-pivoting QR reports the rank.
PolyFit fitPolynomial(const std::vector<double>& u, const std::vector<double>& y, int order) {
  PolyFit fit;
  const auto n = static_cast<Eigen::Index>(u.size());
  const int k = order + 1;
  if (n < k) {
    fit.problem = "needs at least " + std::to_string(k) + " samples, got " + std::to_string(n);
    return fit;
  }
  double scale = 0.0;
  for (double v : u)
    scale = std::max(scale, std::abs(v));
  if (scale == 0.0)
    scale = 1.0;
  Eigen::MatrixXd a(n, k);
  Eigen::VectorXd b(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double t = u[static_cast<std::size_t>(i)] / scale;
    double power = 1.0;
    for (int j = 0; j < k; ++j) {
      a(i, j) = power;
      power *= t;
    }
    b(i) = y[static_cast<std::size_t>(i)];
  }
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(a);
  qr.setThreshold(1e-10);
  if (qr.rank() < k) {
    fit.problem = "the samples do not determine a degree-" + std::to_string(order) +
                  " polynomial (too few distinct values)";
    return fit;
  }
  const Eigen::VectorXd beta = qr.solve(b);
  fit.coefficients.resize(static_cast<std::size_t>(k));
  double power = 1.0;
  for (int j = 0; j < k; ++j) {
    fit.coefficients[static_cast<std::size_t>(j)] = beta(j) / power;
    power *= scale;
  }
  fit.rms = std::sqrt((a * beta - b).squaredNorm() / static_cast<double>(n));
  fit.ok = true;
  return fit;
}

std::string trim(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string::npos)
    return {};
  const auto last = s.find_last_not_of(" \t\r");
  return s.substr(first, last - first + 1);
}

std::vector<std::string> splitCsv(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream stream(line);
  std::string field;
  while (std::getline(stream, field, ','))
    fields.push_back(trim(field));
  if (!line.empty() && line.back() == ',')
    fields.emplace_back();
  return fields;
}

std::optional<double> parseNumber(const std::string& s) {
  double v = 0.0;
  const char* end = s.data() + s.size();
  const auto [ptr, ec] = std::from_chars(s.data(), end, v);
  if (ec != std::errc{} || ptr != end || !std::isfinite(v))
    return std::nullopt;
  return v;
}

}  // namespace

double GyroCalibration::compensateRadps(double indicated_radps, double temperature_c) const {
  return degToRad(compensateDps(radToDeg(indicated_radps), temperature_c));
}

ScaleFactorFit fitScaleFactorCurve(std::span<const RateTableSample> samples) {
  ScaleFactorFit out;
  std::vector<double> x, y;
  for (const RateTableSample& s : samples) {
    if (!std::isfinite(s.true_dps) || !std::isfinite(s.indicated_dps)) {
      ++out.skipped;
      continue;
    }
    x.push_back(s.indicated_dps);
    y.push_back(s.true_dps - s.indicated_dps);
  }
  out.used = x.size();
  if (out.skipped > 0)
    out.diagnostics.push_back(std::to_string(out.skipped) + " non-finite samples skipped");
  const PolyFit fit = fitPolynomial(x, y, 3);
  if (!fit.ok) {
    out.diagnostics.push_back("scale-factor fit: " + fit.problem);
    return out;
  }
  out.curve.bias_dps = fit.coefficients[0];
  out.curve.a1 = fit.coefficients[1];
  out.curve.a2_per_dps = fit.coefficients[2];
  out.curve.a3_per_dps2 = fit.coefficients[3];
  out.rms_residual_dps = fit.rms;
  out.ok = true;
  return out;
}

TemperatureBiasFit fitTemperatureBias(std::span<const RestSample> samples, int order,
                                      const ScaleFactorCurve& curve) {
  if (order != 1 && order != 2)
    throw std::invalid_argument("fitTemperatureBias: order must be 1 (line) or 2 (quadratic)");
  TemperatureBiasFit out;
  std::vector<double> t, y;
  for (const RestSample& s : samples) {
    if (!std::isfinite(s.temperature_c) || !std::isfinite(s.indicated_dps)) {
      ++out.skipped;
      continue;
    }
    t.push_back(s.temperature_c);
    y.push_back(s.indicated_dps + curve.correction(s.indicated_dps));
  }
  out.used = t.size();
  if (out.skipped > 0)
    out.diagnostics.push_back(std::to_string(out.skipped) + " non-finite samples skipped");
  const PolyFit fit = fitPolynomial(t, y, order);
  if (!fit.ok) {
    out.diagnostics.push_back("temperature-bias fit: " + fit.problem);
    return out;
  }
  out.bias.c0_dps = fit.coefficients[0];
  out.bias.c1_dps_per_c = fit.coefficients[1];
  out.bias.c2_dps_per_c2 = order == 2 ? fit.coefficients[2] : 0.0;
  out.rms_residual_dps = fit.rms;
  out.ok = true;
  return out;
}

CalibrationLog parseCalibrationCsv(const std::string& text) {
  CalibrationLog log;
  std::stringstream stream(text);
  std::string line;
  int line_no = 0;
  std::optional<std::vector<std::string>> header;
  int col_true = -1, col_indicated = -1, col_temperature = -1;
  while (std::getline(stream, line)) {
    ++line_no;
    const std::string trimmed = trim(line);
    if (trimmed.empty() || trimmed.front() == '#')
      continue;
    const std::vector<std::string> fields = splitCsv(trimmed);
    if (!header) {
      header = fields;
      for (std::size_t i = 0; i < fields.size(); ++i) {
        if (fields[i] == "true_dps")
          col_true = static_cast<int>(i);
        else if (fields[i] == "indicated_dps")
          col_indicated = static_cast<int>(i);
        else if (fields[i] == "temperature_c")
          col_temperature = static_cast<int>(i);
      }
      if (col_indicated < 0 || (col_true < 0 && col_temperature < 0)) {
        log.diagnostics.push_back("line " + std::to_string(line_no) +
                                  ": header needs indicated_dps and true_dps (rate table) or "
                                  "temperature_c (stationary run)");
        return log;
      }
      continue;
    }
    const auto get = [&](int col) -> std::optional<double> {
      if (col < 0 || static_cast<std::size_t>(col) >= fields.size())
        return std::nullopt;
      return parseNumber(fields[static_cast<std::size_t>(col)]);
    };
    const auto indicated = get(col_indicated);
    if (col_true >= 0) {
      const auto truth = get(col_true);
      if (!indicated || !truth) {
        log.diagnostics.push_back("line " + std::to_string(line_no) +
                                  ": true_dps/indicated_dps missing or not a finite number");
        continue;
      }
      log.rate_table.push_back({*truth, *indicated});
    } else {
      const auto temperature = get(col_temperature);
      if (!indicated || !temperature) {
        log.diagnostics.push_back("line " + std::to_string(line_no) +
                                  ": temperature_c/indicated_dps missing or not a finite number");
        continue;
      }
      log.rest.push_back({*temperature, *indicated});
    }
  }
  if (!header)
    log.diagnostics.push_back("empty log: no header line");
  return log;
}

}  // namespace irgs
