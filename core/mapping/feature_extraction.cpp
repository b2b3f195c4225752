#include "core/mapping/feature_extraction.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace irgs {
namespace {

// Wall evidence: cell centres (world metres) and their log-odds.
struct Evidence {
  std::vector<Vec2> p;
  std::vector<float> w;
};

Evidence collectEvidence(const OccupancyGrid& grid, const FeatureExtractionParams& params) {
  Evidence ev;
  const OccupancyGrid::CellRect rect = grid.observedCellRect();
  if (rect.empty())
    return ev;
  const int m = static_cast<int>(std::ceil(params.free_support_distance_m / grid.resolution_m()));
  const int m2 = m * m;
  // Read in bands of one tile height (plus the support margin above and below) so a large grid
  // never needs one huge buffer.
  std::vector<float> buffer;
  for (int row0 = rect.row0; row0 <= rect.row1; row0 += OccupancyGrid::kTileSize) {
    const int row1 = std::min(rect.row1, row0 + OccupancyGrid::kTileSize - 1);
    const OccupancyGrid::CellRect band{rect.col0, std::max(rect.row0, row0 - m), rect.col1,
                                       std::min(rect.row1, row1 + m)};
    grid.copyLogOdds(band, buffer);
    const int w = band.width(), h = band.height();
    const auto at = [&](int c, int r) {
      return buffer[static_cast<std::size_t>(r) * static_cast<std::size_t>(w) +
                    static_cast<std::size_t>(c)];
    };
    for (int r = row0 - band.row0; r <= row1 - band.row0; ++r)
      for (int c = 0; c < w; ++c) {
        const float l = at(c, r);
        if (!(l > params.occupied_log_odds))  // NaN (unobserved) fails too
          continue;
        bool supported = false;
        for (int dr = -m; dr <= m && !supported; ++dr) {
          const int rr = r + dr;
          if (rr < 0 || rr >= h)
            continue;
          for (int dc = -m; dc <= m && !supported; ++dc) {
            const int cc = c + dc;
            supported =
                cc >= 0 && cc < w && dr * dr + dc * dc <= m2 && at(cc, rr) < params.free_log_odds;
          }
        }
        if (!supported)
          continue;
        ev.p.push_back(grid.cellCentre({band.col0 + c, band.row0 + r}));
        ev.w.push_back(l);
      }
  }
  return ev;
}

// A line in normal form fitted by weighted total least squares.
struct LineFit {
  Vec2 centroid = Vec2::Zero();
  Vec2 dir = Vec2::UnitX();
  Vec2 normal = Vec2::UnitY();
  double offset = 0.0;  // normal . p
  double weight = 0.0;
  bool ok = false;

  double distance(const Vec2& p) const { return normal.dot(p) - offset; }
  double along(const Vec2& p) const { return dir.dot(p - centroid); }
};

LineFit fitLine(const Evidence& ev, const std::vector<std::size_t>& idx) {
  LineFit fit;
  double sw = 0.0;
  Vec2 mean = Vec2::Zero();
  for (const std::size_t i : idx) {
    sw += ev.w[i];
    mean += ev.w[i] * ev.p[i];
  }
  if (idx.size() < 2 || !(sw > 0.0))
    return fit;
  mean /= sw;
  double sxx = 0.0, sxy = 0.0, syy = 0.0;
  for (const std::size_t i : idx) {
    const Vec2 d = ev.p[i] - mean;
    sxx += ev.w[i] * d.x() * d.x();
    sxy += ev.w[i] * d.x() * d.y();
    syy += ev.w[i] * d.y() * d.y();
  }
  // Direction of the largest eigenvector of the 2x2 scatter matrix.
  const double angle = 0.5 * std::atan2(2.0 * sxy, sxx - syy);
  fit.centroid = mean;
  fit.dir = Vec2(std::cos(angle), std::sin(angle));
  fit.normal = Vec2(-fit.dir.y(), fit.dir.x());
  fit.offset = fit.normal.dot(mean);
  fit.weight = sw;
  fit.ok = true;
  return fit;
}

// Weighted Hough accumulator over (angle, offset from the evidence centre).
class Hough {
 public:
  static constexpr double kMaxBins = 1 << 24;

  Hough(const Evidence& ev, double angle_step, double rho_step) : ev_(ev), rho_step_(rho_step) {
    Box2 box;
    for (const Vec2& p : ev.p)
      box.extend(p);
    centre_ = 0.5 * (box.min + box.max);
    angles_ = std::max(1, static_cast<int>(std::ceil(kPi / angle_step)));
    // The accumulator stays under kMaxBins however far apart the evidence lies (a grid with
    // stray cells kilometres away): the candidate search gets coarser, the refits stay exact.
    const double half_diagonal = 0.5 * box.size().norm();
    rho_step = std::max(rho_step, 2.0 * (half_diagonal + 1.0) * angles_ / kMaxBins);
    rho_step_ = rho_step;
    rho_max_ = half_diagonal + 2.0 * rho_step;
    rhos_ = static_cast<int>(std::ceil(2.0 * rho_max_ / rho_step)) + 1;
    cos_.resize(static_cast<std::size_t>(angles_));
    sin_.resize(static_cast<std::size_t>(angles_));
    for (int k = 0; k < angles_; ++k) {
      const double a = kPi * k / angles_;
      cos_[static_cast<std::size_t>(k)] = std::cos(a);
      sin_[static_cast<std::size_t>(k)] = std::sin(a);
    }
    acc_.assign(static_cast<std::size_t>(angles_) * static_cast<std::size_t>(rhos_), 0.0f);
    suppressed_.assign(acc_.size(), 0);
    row_dirty_.assign(static_cast<std::size_t>(angles_), 1);
    row_best_.assign(static_cast<std::size_t>(angles_), -1.0f);
    row_arg_.assign(static_cast<std::size_t>(angles_), 0);
    for (std::size_t i = 0; i < ev.p.size(); ++i)
      vote(i, ev.w[i]);
  }

  void withdraw(std::size_t i) { vote(i, -ev_.w[i]); }

  struct Peak {
    double weight = 0.0;
    int angle = 0;
    int rho = 0;
  };
  // The strongest unsuppressed bin. Each angle row keeps its maximum and is rescanned only
  // after it changed (a withdrawal changes every row, a suppression three), so the many peaks
  // that yield no line cost three row scans instead of a full accumulator scan.
  Peak strongest() {
    Peak best{-1.0, 0, 0};
    for (int a = 0; a < angles_; ++a) {
      const auto k = static_cast<std::size_t>(a);
      if (row_dirty_[k] != 0) {
        row_best_[k] = -1.0f;
        row_arg_[k] = 0;
        for (int r = 0; r < rhos_; ++r) {
          const std::size_t b = bin(a, r);
          if (suppressed_[b] == 0 && acc_[b] > row_best_[k]) {
            row_best_[k] = acc_[b];
            row_arg_[k] = r;
          }
        }
        row_dirty_[k] = 0;
      }
      if (row_best_[k] > best.weight)
        best = {row_best_[k], a, row_arg_[k]};
    }
    return best;
  }
  // Never offers the bin (and its neighbours, which hold the same non-line) again.
  void suppress(const Peak& peak) {
    for (int da = -1; da <= 1; ++da)
      for (int dr = -1; dr <= 1; ++dr) {
        const int a = (peak.angle + da + angles_) % angles_;
        const int r = peak.rho + dr;
        if (r >= 0 && r < rhos_)
          suppressed_[bin(a, r)] = 1;
        row_dirty_[static_cast<std::size_t>(a)] = 1;
      }
  }
  // The line of a bin: normal (cos a, sin a), world offset normal . p.
  LineFit line(const Peak& peak) const {
    LineFit fit;
    const auto k = static_cast<std::size_t>(peak.angle);
    fit.normal = Vec2(cos_[k], sin_[k]);
    fit.dir = Vec2(fit.normal.y(), -fit.normal.x());
    const double rho = (peak.rho + 0.5) * rho_step_ - rho_max_;
    fit.offset = rho + fit.normal.dot(centre_);
    fit.centroid = centre_ + rho * fit.normal;
    fit.ok = true;
    return fit;
  }

 private:
  std::size_t bin(int a, int r) const {
    return static_cast<std::size_t>(a) * static_cast<std::size_t>(rhos_) +
           static_cast<std::size_t>(r);
  }
  void vote(std::size_t i, float w) {
    const double x = ev_.p[i].x() - centre_.x(), y = ev_.p[i].y() - centre_.y();
    for (int k = 0; k < angles_; ++k) {
      const double rho =
          x * cos_[static_cast<std::size_t>(k)] + y * sin_[static_cast<std::size_t>(k)];
      const int r = std::clamp(static_cast<int>((rho + rho_max_) / rho_step_), 0, rhos_ - 1);
      acc_[bin(k, r)] += w;
    }
    std::fill(row_dirty_.begin(), row_dirty_.end(), std::uint8_t{1});
  }

  const Evidence& ev_;
  double rho_step_;
  Vec2 centre_ = Vec2::Zero();
  double rho_max_ = 0.0;
  int angles_ = 0;
  int rhos_ = 0;
  std::vector<double> cos_, sin_;
  std::vector<float> acc_;
  std::vector<std::uint8_t> suppressed_;
  std::vector<std::uint8_t> row_dirty_;
  std::vector<float> row_best_;
  std::vector<int> row_arg_;
};

// A line under construction: its fit and the evidence supporting it.
struct LineBuild {
  LineFit fit;
  std::vector<std::size_t> support;
  double t0 = 0.0, t1 = 0.0;  // extent along fit.dir from fit.centroid
  double free_left = 0.0, free_right = 0.0;
};

void extent(const Evidence& ev, LineBuild& line) {
  line.t0 = std::numeric_limits<double>::infinity();
  line.t1 = -std::numeric_limits<double>::infinity();
  for (const std::size_t i : line.support) {
    const double t = line.fit.along(ev.p[i]);
    line.t0 = std::min(line.t0, t);
    line.t1 = std::max(line.t1, t);
  }
}

Vec2 lineStart(const LineBuild& l) {
  return l.fit.centroid + l.t0 * l.fit.dir;
}
Vec2 lineEnd(const LineBuild& l) {
  return l.fit.centroid + l.t1 * l.fit.dir;
}

// Share of the resolution-sized bins along [t0, t1] holding at least one cell.
double fill(const std::vector<double>& sorted_t, double res) {
  if (sorted_t.empty())
    return 0.0;
  const double length = sorted_t.back() - sorted_t.front();
  const auto bins = static_cast<std::size_t>(std::floor(length / res)) + 1;
  std::size_t occupied = 0;
  long long last = -1;
  for (const double t : sorted_t) {
    const auto b = static_cast<long long>(std::floor((t - sorted_t.front()) / res));
    if (b != last) {
      ++occupied;
      last = b;
    }
  }
  return static_cast<double>(occupied) / static_cast<double>(bins);
}

class Extractor {
 public:
  Extractor(const OccupancyGrid& grid, const FeatureExtractionParams& params)
      : grid_(grid), prm_(params), res_(grid.resolution_m()) {}

  FeatureExtractionResult run() {
    FeatureExtractionResult result;
    ev_ = collectEvidence(grid_, prm_);
    result.evidence_cells = ev_.p.size();
    if (ev_.p.size() < 2)
      return result;
    used_.assign(ev_.p.size(), 0);
    result.truncated = peelLines();
    mergeCollinear();
    dropUnseenAndGhostLines();
    for (const LineBuild& l : lines_)
      result.assigned_cells += l.support.size();
    for (const LineBuild& l : lines_)
      result.lines.push_back(describe(l));
    findPoints(result);
    return result;
  }

 private:
  // Step 2: Hough peaks -> line pieces. Returns true when a cap stopped it.
  bool peelLines() {
    Hough hough(ev_, prm_.hough_angle_step_rad, std::max(prm_.hough_rho_step_m, res_));
    const double min_cells = std::ceil(prm_.min_fill * prm_.min_line_length_m / res_);
    // A bin may hold only part of a line's cells (the band is wider than a bin): half of the
    // weakest acceptable line is the floor for a peak worth examining.
    const double min_peak = 0.5 * prm_.occupied_log_odds * min_cells;
    const long max_iterations = 4L * prm_.max_lines + 4000L;
    for (long iter = 0;; ++iter) {
      if (static_cast<int>(lines_.size()) >= prm_.max_lines || iter >= max_iterations)
        return true;
      const Hough::Peak peak = hough.strongest();
      if (peak.weight < min_peak)
        return false;
      LineFit fit = hough.line(peak);
      std::vector<std::size_t> band =
          gather(fit, prm_.inlier_distance_m + 0.5 * prm_.hough_rho_step_m, nullptr);
      for (int refit = 0; refit < 2 && band.size() >= 2; ++refit) {
        const LineFit better = fitLine(ev_, band);
        if (!better.ok)
          break;
        fit = better;
        band = gather(fit, prm_.inlier_distance_m, nullptr);
      }
      bool accepted = false;
      for (std::vector<std::size_t>& piece : splitAtGaps(fit, band)) {
        LineBuild line;
        line.fit = fitLine(ev_, piece);
        if (!line.fit.ok)
          continue;
        // Re-gather around the refitted piece only (not the whole infinite line).
        line.support = piece;
        extent(ev_, line);
        std::vector<std::size_t> support = gather(line.fit, prm_.inlier_distance_m, &line);
        if (support.size() < 2)
          continue;
        line.support = std::move(support);
        line.fit = fitLine(ev_, line.support);
        if (!line.fit.ok)
          continue;
        extent(ev_, line);
        for (const std::size_t i : line.support) {
          used_[i] = 1;
          hough.withdraw(i);
        }
        lines_.push_back(std::move(line));
        accepted = true;
      }
      if (!accepted)
        hough.suppress(peak);
    }
  }

  // Unused evidence within `distance` of the line; with `within`, only cells projecting inside
  // its extent (plus two cells).
  std::vector<std::size_t> gather(const LineFit& fit, double distance,
                                  const LineBuild* within) const {
    std::vector<std::size_t> out;
    for (std::size_t i = 0; i < ev_.p.size(); ++i) {
      if (used_[i] != 0 || std::abs(fit.distance(ev_.p[i])) > distance)
        continue;
      if (within != nullptr) {
        const double t = within->fit.along(ev_.p[i]);
        if (t < within->t0 - 2.0 * res_ || t > within->t1 + 2.0 * res_)
          continue;
      }
      out.push_back(i);
    }
    return out;
  }

  // The band split where consecutive cells along the line are more than max_gap_m apart;
  // only pieces long and dense enough are returned.
  std::vector<std::vector<std::size_t>> splitAtGaps(const LineFit& fit,
                                                    std::vector<std::size_t> band) const {
    std::vector<std::vector<std::size_t>> pieces;
    if (band.empty())
      return pieces;
    std::vector<double> t(band.size());
    for (std::size_t k = 0; k < band.size(); ++k)
      t[k] = fit.along(ev_.p[band[k]]);
    std::vector<std::size_t> order(band.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::stable_sort(order.begin(), order.end(),
                     [&t](std::size_t a, std::size_t b) { return t[a] < t[b]; });
    std::size_t start = 0;
    for (std::size_t k = 1; k <= order.size(); ++k) {
      if (k < order.size() && t[order[k]] - t[order[k - 1]] <= prm_.max_gap_m)
        continue;
      std::vector<double> ts;
      std::vector<std::size_t> piece;
      for (std::size_t q = start; q < k; ++q) {
        ts.push_back(t[order[q]]);
        piece.push_back(band[order[q]]);
      }
      if (ts.back() - ts.front() >= prm_.min_line_length_m && fill(ts, res_) >= prm_.min_fill)
        pieces.push_back(std::move(piece));
      start = k;
    }
    return pieces;
  }

  // Step 3.
  bool mergeable(const LineBuild& p, const LineBuild& q) const {
    if (std::abs(p.fit.dir.dot(q.fit.dir)) < std::cos(prm_.merge_angle_rad))
      return false;
    for (const auto& [a, b] : {std::pair{&p, &q}, std::pair{&q, &p}}) {
      if (std::abs(a->fit.distance(lineStart(*b))) > prm_.merge_offset_m ||
          std::abs(a->fit.distance(lineEnd(*b))) > prm_.merge_offset_m)
        return false;
    }
    const double s0 = p.fit.along(lineStart(q)), s1 = p.fit.along(lineEnd(q));
    const double g0 = std::min(s0, s1) - p.t1, g1 = p.t0 - std::max(s0, s1);
    const double gap = std::max({0.0, g0, g1});
    if (gap <= prm_.max_gap_m)
      return true;
    if (gap > prm_.bridge_gap_m)
      return false;
    // The gap runs from p's end to q's start (or q's end to p's start).
    const double from = g0 >= g1 ? p.t1 : std::max(s0, s1);
    int left = 0, right = 0;
    for (double t = from + 0.5 * prm_.probe_distance_m; t < from + gap; t += 0.05) {
      const Vec2 x = p.fit.centroid + t * p.fit.dir;
      left += knownFree(x + prm_.probe_distance_m * p.fit.normal) ? 1 : 0;
      right += knownFree(x - prm_.probe_distance_m * p.fit.normal) ? 1 : 0;
    }
    return left == 0 || right == 0;
  }

  void mergeCollinear() {
    bool changed = true;
    while (changed) {
      changed = false;
      for (std::size_t i = 0; i < lines_.size() && !changed; ++i)
        for (std::size_t j = i + 1; j < lines_.size() && !changed; ++j) {
          if (!mergeable(lines_[i], lines_[j]))
            continue;
          LineBuild merged;
          merged.support = lines_[i].support;
          merged.support.insert(merged.support.end(), lines_[j].support.begin(),
                                lines_[j].support.end());
          merged.fit = fitLine(ev_, merged.support);
          if (!merged.fit.ok)
            continue;
          extent(ev_, merged);
          lines_[i] = std::move(merged);
          lines_.erase(lines_.begin() + static_cast<std::ptrdiff_t>(j));
          changed = true;
        }
    }
  }

  // Mean log-odds of the observed cells in the 3x3 block around p; NaN when fewer than five
  // of them are observed or p is not addressable.
  double probe(const Vec2& p) const {
    if (!grid_.isAddressable(p, 2.0 * res_))
      return std::numeric_limits<double>::quiet_NaN();
    const Cell c = grid_.cellAt(p);
    double sum = 0.0;
    int n = 0;
    for (int dr = -1; dr <= 1; ++dr)
      for (int dc = -1; dc <= 1; ++dc) {
        const Cell k{c.col + dc, c.row + dr};
        if (!grid_.observed(k))
          continue;
        sum += grid_.logOdds(k);
        ++n;
      }
    return n >= 5 ? sum / n : std::numeric_limits<double>::quiet_NaN();
  }
  bool knownFree(const Vec2& p) const { return probe(p) < prm_.free_log_odds; }

  ExtractedLine describe(const LineBuild& l) const {
    ExtractedLine out;
    out.segment = {lineStart(l), lineEnd(l)};
    out.normal = l.fit.normal;
    out.offset_m = l.fit.offset;
    out.weight = l.fit.weight;
    out.cells = static_cast<int>(l.support.size());
    double sq = 0.0;
    for (const std::size_t i : l.support)
      sq += ev_.w[i] * std::pow(l.fit.distance(ev_.p[i]), 2);
    out.rms_m = l.fit.weight > 0.0 ? std::sqrt(sq / l.fit.weight) : 0.0;
    out.free_left = l.free_left;
    out.free_right = l.free_right;
    return out;
  }

  // Share of the probes beside the line, per side, that are known free.
  void freeSides(LineBuild& l) const {
    const double length = l.t1 - l.t0;
    const double margin = std::min(0.1, 0.25 * length);
    const double step = std::max(res_, 0.05);
    int samples = 0, left = 0, right = 0;
    for (double t = l.t0 + margin; t <= l.t1 - margin + 1e-9; t += step) {
      const Vec2 p = l.fit.centroid + t * l.fit.dir;
      ++samples;
      left += knownFree(p + prm_.probe_distance_m * l.fit.normal) ? 1 : 0;
      right += knownFree(p - prm_.probe_distance_m * l.fit.normal) ? 1 : 0;
    }
    l.free_left = samples > 0 ? static_cast<double>(left) / samples : 0.0;
    l.free_right = samples > 0 ? static_cast<double>(right) / samples : 0.0;
  }

  void dropUnseenAndGhostLines() {
    for (LineBuild& l : lines_)
      freeSides(l);
    std::vector<std::uint8_t> drop(lines_.size(), 0);
    for (std::size_t a = 0; a < lines_.size(); ++a) {
      const LineBuild& la = lines_[a];
      if (std::max(la.free_left, la.free_right) < prm_.min_free_side) {
        drop[a] = 1;
        continue;
      }
      const Vec2 mid = la.fit.centroid + 0.5 * (la.t0 + la.t1) * la.fit.dir;
      const double len_a = la.t1 - la.t0;
      for (std::size_t b = 0; b < lines_.size() && drop[a] == 0; ++b) {
        const LineBuild& lb = lines_[b];
        if (b == a || lb.fit.weight <= la.fit.weight ||
            std::abs(la.fit.dir.dot(lb.fit.dir)) < std::cos(2.0 * prm_.merge_angle_rad))
          continue;
        const double side = lb.fit.distance(mid);
        if (std::abs(side) > prm_.ghost_distance_m)
          continue;
        if ((side > 0.0 ? lb.free_left : lb.free_right) < prm_.min_free_side)
          continue;  // a is behind b's face, or b is not seen from a's side
        const double s0 = lb.fit.along(lineStart(la)), s1 = lb.fit.along(lineEnd(la));
        const double overlap =
            std::min(lb.t1, std::max(s0, s1)) - std::max(lb.t0, std::min(s0, s1));
        if (overlap >= 0.5 * len_a)
          drop[a] = 1;
      }
    }
    std::vector<LineBuild> kept;
    for (std::size_t i = 0; i < lines_.size(); ++i)
      if (drop[i] == 0)
        kept.push_back(std::move(lines_[i]));
    lines_ = std::move(kept);
  }

  // Steps 4 and 5.
  void findPoints(FeatureExtractionResult& result) const {
    const std::size_t n = lines_.size();
    std::vector<std::array<bool, 2>> joined(n, {false, false});  // [0] start, [1] end
    std::vector<ExtractedPoint> raw;
    const double reach = prm_.junction_reach_m;
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j) {
        const LineBuild& li = lines_[i];
        const LineBuild& lj = lines_[j];
        const double den = cross(li.fit.dir, lj.fit.dir);
        if (std::abs(den) < std::sin(degToRad(10.0)))
          continue;  // (nearly) parallel: no crossing worth a junction
        const Vec2 ai = lineStart(li), aj = lineStart(lj);
        const double ti = cross(aj - ai, lj.fit.dir) / den;
        const double tj = cross(aj - ai, li.fit.dir) / den;
        const double li_len = li.t1 - li.t0, lj_len = lj.t1 - lj.t0;
        const auto outside = [](double t, double len) { return std::max({0.0, -t, t - len}); };
        if (outside(ti, li_len) > reach || outside(tj, lj_len) > reach)
          continue;
        const Vec2 x = ai + ti * li.fit.dir;
        if (ti < reach)
          joined[i][0] = true;
        if (li_len - ti < reach)
          joined[i][1] = true;
        if (tj < reach)
          joined[j][0] = true;
        if (lj_len - tj < reach)
          joined[j][1] = true;
        const auto arms = [reach](const LineBuild& l, double t) {
          std::vector<Vec2> a;
          if (t >= reach)
            a.push_back(-l.fit.dir);
          if (l.t1 - l.t0 - t >= reach)
            a.push_back(l.fit.dir);
          if (a.empty())
            a.push_back(t > 0.5 * (l.t1 - l.t0) ? Vec2(-l.fit.dir) : l.fit.dir);
          return a;
        };
        const std::vector<Vec2> arms_i = arms(li, ti), arms_j = arms(lj, tj);
        bool concave = false;
        double wedge = 0.0;
        Vec2 bisector = Vec2::Zero();
        for (const Vec2& u : arms_i)
          for (const Vec2& v : arms_j) {
            const double angle = std::acos(std::clamp(u.dot(v), -1.0, 1.0));
            if (angle < prm_.corner_min_angle_rad || angle > prm_.corner_max_angle_rad)
              continue;
            const Vec2 b = (u + v).normalized();
            if (!concave) {
              wedge = angle;
              bisector = b;
            }
            if (!concave && knownFree(x + prm_.probe_distance_m * b)) {
              concave = true;
              wedge = angle;
              bisector = b;
            }
          }
        if (wedge == 0.0)
          continue;  // no wedge in the corner angle range
        const int a = static_cast<int>(i), b = static_cast<int>(j);
        if (concave) {
          raw.push_back({PointFeatureKind::kCorner, x, a, b, wedge});
        } else if (arms_i.size() == 1 && arms_j.size() == 1 &&
                   knownFree(x - prm_.probe_distance_m * bisector) &&
                   !knownFree(x + prm_.probe_distance_m * bisector)) {
          raw.push_back({PointFeatureKind::kEdge, x, a, b, wedge});
        }
      }
    // Free line ends.
    for (std::size_t i = 0; i < n; ++i) {
      const LineBuild& l = lines_[i];
      for (int end = 0; end < 2; ++end) {
        if (joined[i][static_cast<std::size_t>(end)])
          continue;
        const Vec2 e = end == 0 ? lineStart(l) : lineEnd(l);
        const Vec2 out = end == 0 ? Vec2(-l.fit.dir) : l.fit.dir;
        bool near_other = false;
        for (std::size_t j = 0; j < n && !near_other; ++j) {
          if (j == i)
            continue;
          const LineBuild& o = lines_[j];
          const double t = std::clamp(o.fit.along(e), o.t0, o.t1);
          near_other = (o.fit.centroid + t * o.fit.dir - e).norm() < reach;
        }
        // Beyond a door jamb or a free-standing wall end there is free space on both sides of
        // the line's continuation; a hole that grazing cones cleared in an outer wall has
        // unknown space behind it.
        const Vec2 beyond = e + prm_.probe_distance_m * out;
        const Vec2 side = prm_.probe_distance_m * l.fit.normal;
        if (near_other || !knownFree(beyond) || !knownFree(beyond + side) ||
            !knownFree(beyond - side))
          continue;
        raw.push_back({PointFeatureKind::kEdge, e, static_cast<int>(i), -1, 0.0});
      }
    }
    // Merge points of one kind that describe the same place (e.g. the two corners of a T).
    std::vector<int> count;
    for (const ExtractedPoint& p : raw) {
      bool merged = false;
      for (std::size_t k = 0; k < result.points.size() && !merged; ++k) {
        ExtractedPoint& q = result.points[k];
        if (q.kind != p.kind || (q.position - p.position).norm() > prm_.point_merge_distance_m)
          continue;
        const double c = count[k];
        q.position = (c * q.position + p.position) / (c + 1.0);
        ++count[k];
        merged = true;
      }
      if (!merged) {
        result.points.push_back(p);
        count.push_back(1);
      }
    }
  }

  const OccupancyGrid& grid_;
  const FeatureExtractionParams& prm_;
  double res_;
  Evidence ev_;
  std::vector<std::uint8_t> used_;
  std::vector<LineBuild> lines_;
};

bool finitePositive(double v) {
  return std::isfinite(v) && v > 0.0;
}

}  // namespace

std::optional<std::string> featureExtractionParamsError(const FeatureExtractionParams& p) {
  if (!std::isfinite(p.occupied_log_odds) || !std::isfinite(p.free_log_odds) ||
      p.free_log_odds >= p.occupied_log_odds)
    return "feature extraction needs finite log-odds with free_log_odds < occupied_log_odds";
  if (p.occupied_log_odds <= 0.0)
    return "feature extraction needs occupied_log_odds > 0 (evidence is weighted by it)";
  for (const auto& [name, v] :
       {std::pair{"hough_angle_step_rad", p.hough_angle_step_rad},
        std::pair{"hough_rho_step_m", p.hough_rho_step_m},
        std::pair{"inlier_distance_m", p.inlier_distance_m}, std::pair{"max_gap_m", p.max_gap_m},
        std::pair{"min_line_length_m", p.min_line_length_m},
        std::pair{"merge_angle_rad", p.merge_angle_rad},
        std::pair{"merge_offset_m", p.merge_offset_m},
        std::pair{"junction_reach_m", p.junction_reach_m},
        std::pair{"probe_distance_m", p.probe_distance_m},
        std::pair{"point_merge_distance_m", p.point_merge_distance_m},
        std::pair{"free_support_distance_m", p.free_support_distance_m},
        std::pair{"bridge_gap_m", p.bridge_gap_m},
        std::pair{"ghost_distance_m", p.ghost_distance_m}})
    if (!finitePositive(v))
      return std::string("feature extraction parameter ") + name + " must be finite and > 0";
  if (p.hough_angle_step_rad > degToRad(10.0))
    return "feature extraction parameter hough_angle_step_rad must be <= 10 deg";
  if (!(p.min_fill > 0.0 && p.min_fill <= 1.0))
    return "feature extraction parameter min_fill must be in (0, 1]";
  if (!(p.corner_min_angle_rad > 0.0 && p.corner_min_angle_rad <= p.corner_max_angle_rad &&
        p.corner_max_angle_rad < kPi))
    return "feature extraction needs 0 < corner_min_angle_rad <= corner_max_angle_rad < pi";
  if (!(p.min_free_side >= 0.0 && p.min_free_side <= 1.0))
    return "feature extraction parameter min_free_side must be in [0, 1]";
  if (p.free_support_distance_m > 1.0)
    return "feature extraction parameter free_support_distance_m must be <= 1 m";
  if (p.max_lines < 1)
    return "feature extraction parameter max_lines must be >= 1";
  return std::nullopt;
}

FeatureExtractionResult extractFeatures(const OccupancyGrid& grid,
                                        const FeatureExtractionParams& params) {
  if (const auto error = featureExtractionParamsError(params))
    throw std::invalid_argument(*error);
  return Extractor(grid, params).run();
}

}  // namespace irgs
