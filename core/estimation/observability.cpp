#include "core/estimation/observability.hpp"

#include <Eigen/SVD>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "core/estimation/dr_error_model.hpp"
#include "core/geometry/types.hpp"
#include "core/sim/random.hpp"

namespace irgs {

namespace {

constexpr std::uint64_t kSegmentStream = 1;

// Reduced row-echelon form of the rows of `m` (partial pivoting, columns left to right).
Eigen::MatrixXd rref(Eigen::MatrixXd m, double tolerance) {
  Eigen::Index row = 0;
  for (Eigen::Index col = 0; col < m.cols() && row < m.rows(); ++col) {
    Eigen::Index pivot = row;
    m.col(col).segment(row, m.rows() - row).cwiseAbs().maxCoeff(&pivot);
    pivot += row;
    if (std::abs(m(pivot, col)) <= tolerance)
      continue;
    if (pivot != row)
      m.row(row).swap(m.row(pivot));
    m.row(row) /= m(row, col);
    for (Eigen::Index r = 0; r < m.rows(); ++r)
      if (r != row)
        m.row(r) -= m(r, col) * m.row(row);
    ++row;
  }
  // Clean round-off so printed zeros are zeros.
  return m.unaryExpr([tolerance](double v) { return std::abs(v) <= tolerance ? 0.0 : v; });
}

}  // namespace

int stateCount(DrModelKind kind) {
  switch (kind) {
    case DrModelKind::kNineState:
      return 9;
    case DrModelKind::kEightState:
      return 8;
    case DrModelKind::kSevenState:
      return 7;
  }
  throw std::invalid_argument("stateCount: unknown model");
}

std::vector<std::string> stateNames(DrModelKind kind) {
  switch (kind) {
    case DrModelKind::kNineState:
      return {"dx", "dy", "dpsi", "S_R", "S_L", "dD", "dphi", "dB_s", "dB_rb"};
    case DrModelKind::kEightState:
      return {"dx", "dy", "dtheta", "S_R", "S_L", "dD", "dB_s", "dB_rb"};
    case DrModelKind::kSevenState:
      return {"dpsi", "S_R", "S_L", "dD", "dphi", "dB_s", "dB_rb"};
  }
  throw std::invalid_argument("stateNames: unknown model");
}

std::vector<DrSegment> randomSegments(int count, std::uint64_t seed, SegmentKind kind,
                                      double wheelbase_m, double dt_s) {
  if (count < 1 || !(wheelbase_m > 0.0) || !std::isfinite(wheelbase_m) || !(dt_s > 0.0) ||
      !std::isfinite(dt_s))
    throw std::invalid_argument("randomSegments: needs count >= 1, wheelbase > 0 and dt > 0");
  SimRandom rng = SimRandom::stream(seed, kSegmentStream);
  std::vector<DrSegment> segments(static_cast<std::size_t>(count));
  for (DrSegment& s : segments) {
    s.right_m = rng.uniform() - 0.5;
    s.left_m = rng.uniform() - 0.5;
    s.psi_rad = kPi * (2.0 * rng.uniform() - 1.0);
    const double independent = 2.0 * rng.uniform() - 1.0;  // drawn always: same R, L, psi
    s.omega_rad =
        kind == SegmentKind::kConsistent ? (s.right_m - s.left_m) / wheelbase_m : independent;
    s.wheelbase_m = wheelbase_m;
    s.dt_s = dt_s;
  }
  return segments;
}

Eigen::MatrixXd drTransitionMatrix(DrModelKind kind, const DrSegment& seg) {
  const double r = seg.right_m, l = seg.left_m, d = seg.wheelbase_m;
  const double c = std::cos(seg.psi_rad), s = std::sin(seg.psi_rad);
  switch (kind) {
    case DrModelKind::kNineState: {
      DrStepGeometry g;
      g.right_m = r;
      g.left_m = l;
      g.psi_rad = seg.psi_rad;
      g.wheelbase_m = d;
      g.omega_rad = seg.omega_rad;
      g.dt_s = seg.dt_s;
      return drTransition(g);
    }
    case DrModelKind::kEightState: {
      // (15), A001-5: [dx, dy, dtheta, S_R, S_L, dD, dB_s, dB_rb], dtheta = dpsi - dphi; the
      // position rows keep (3)'s coupling with dtheta in place of dpsi (001's simplification).
      Eigen::MatrixXd f = Eigen::MatrixXd::Identity(8, 8);
      f(0, 2) = -s * 0.5 * (r + l);
      f(0, 3) = c * 0.5 * r;
      f(0, 4) = c * 0.5 * l;
      f(1, 2) = c * 0.5 * (r + l);
      f(1, 3) = s * 0.5 * r;
      f(1, 4) = s * 0.5 * l;
      f(2, 3) = r / d;
      f(2, 4) = -l / d;
      f(2, 5) = (l - r) / (d * d);
      f(2, 6) = -seg.omega_rad;
      f(2, 7) = -seg.dt_s;
      return f;
    }
    case DrModelKind::kSevenState: {
      // (17), A001-5: [dpsi, S_R, S_L, dD, dphi, dB_s, dB_rb].
      Eigen::MatrixXd f = Eigen::MatrixXd::Identity(7, 7);
      f(0, 1) = r / d;
      f(0, 2) = -l / d;
      f(0, 3) = (l - r) / (d * d);
      f(4, 5) = seg.omega_rad;
      f(4, 6) = seg.dt_s;
      return f;
    }
  }
  throw std::invalid_argument("drTransitionMatrix: unknown model");
}

Eigen::RowVectorXd drMeasurementMatrix(DrModelKind kind) {
  // Z = psi_enc - phi_gyro with delta = true - computed (A001-4).
  switch (kind) {
    case DrModelKind::kNineState:
      return drMeasurementRow();
    case DrModelKind::kEightState: {
      Eigen::RowVectorXd h = Eigen::RowVectorXd::Zero(8);
      h(2) = -1.0;  // (16): Z = -(dpsi - dphi) = -dtheta
      return h;
    }
    case DrModelKind::kSevenState: {
      Eigen::RowVectorXd h = Eigen::RowVectorXd::Zero(7);
      h(0) = -1.0;  // (18)
      h(4) = 1.0;
      return h;
    }
  }
  throw std::invalid_argument("drMeasurementMatrix: unknown model");
}

Eigen::MatrixXd totalObservabilityMatrix(DrModelKind kind, const std::vector<DrSegment>& segments) {
  if (segments.empty())
    throw std::invalid_argument("totalObservabilityMatrix: no segments");
  const int n = stateCount(kind);
  const Eigen::RowVectorXd h = drMeasurementMatrix(kind);
  Eigen::MatrixXd tom(static_cast<Eigen::Index>(segments.size()) * n, n);
  Eigen::MatrixXd before = Eigen::MatrixXd::Identity(n, n);  // F_(j-1)^(n-1) ... F_1^(n-1)
  Eigen::Index row = 0;
  for (const DrSegment& seg : segments) {
    if (!(seg.wheelbase_m > 0.0) || !std::isfinite(seg.wheelbase_m))
      throw std::invalid_argument("totalObservabilityMatrix: wheelbase must be > 0");
    const Eigen::MatrixXd f = drTransitionMatrix(kind, seg);
    // (13) Q_j = [H; H F_j; ...; H F_j^(n-1)], times the transition to the segment's start.
    Eigen::MatrixXd power = Eigen::MatrixXd::Identity(n, n);
    for (int i = 0; i < n; ++i) {
      tom.row(row++) = h * power * before;
      if (i + 1 < n)
        power = f * power;
    }
    before = power * before;  // F_j^(n-1) ... (14)
  }
  return tom;
}

ObservabilityReport analyseObservability(DrModelKind kind, const std::vector<DrSegment>& segments,
                                         double relative_tolerance) {
  if (!(relative_tolerance > 0.0 && relative_tolerance < 1.0))
    throw std::invalid_argument("analyseObservability: relative_tolerance must be in (0, 1)");
  const Eigen::MatrixXd tom = totalObservabilityMatrix(kind, segments);
  const int n = stateCount(kind);
  // Columns to unit norm: states in metres, radians and ratios are compared fairly.
  Eigen::VectorXd scale(n);
  for (int j = 0; j < n; ++j) {
    const double norm = tom.col(j).norm();
    scale(j) = norm > 0.0 ? 1.0 / norm : 1.0;
  }
  const Eigen::MatrixXd scaled = tom * scale.asDiagonal();
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(scaled, Eigen::ComputeFullV);
  const Eigen::VectorXd sv = svd.singularValues();
  ObservabilityReport report;
  report.states = n;
  report.tolerance = relative_tolerance * (sv.size() > 0 ? sv(0) : 0.0);
  for (Eigen::Index i = 0; i < sv.size(); ++i) {
    report.singular_values.push_back(sv(i));
    if (sv(i) > report.tolerance)
      ++report.rank;
  }
  const int nullity = n - report.rank;
  if (nullity > 0) {
    // Null directions in the original (unscaled) state coordinates, then in readable form.
    const Eigen::MatrixXd v = scale.asDiagonal() * svd.matrixV().rightCols(nullity);
    report.null_space = rref(v.transpose(), 1e-9).transpose();
  } else {
    report.null_space = Eigen::MatrixXd(n, 0);
  }
  return report;
}

std::string formatReport(DrModelKind kind, const ObservabilityReport& report) {
  const std::vector<std::string> names = stateNames(kind);
  std::string out = std::to_string(report.states) +
                    "-state model: rank(TOM) = " + std::to_string(report.rank) + " of " +
                    std::to_string(report.states) + "\n";
  char buffer[64];
  out += "  singular values (column-normalised):";
  for (double s : report.singular_values) {
    std::snprintf(buffer, sizeof buffer, " %.3g", s);
    out += buffer;
  }
  out += "\n";
  for (Eigen::Index c = 0; c < report.null_space.cols(); ++c) {
    out += "  null direction " + std::to_string(c + 1) + ":";
    for (Eigen::Index i = 0; i < report.null_space.rows(); ++i) {
      const double v = report.null_space(i, c);
      if (v == 0.0)
        continue;
      std::snprintf(buffer, sizeof buffer, " %s=%.6g", names[static_cast<std::size_t>(i)].c_str(),
                    v);
      out += buffer;
    }
    out += "\n";
  }
  return out;
}

}  // namespace irgs
