#include "core/estimation/observability.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <stdexcept>

namespace irgs {
namespace {

constexpr double kD = 0.5;

// True when v lies in the span of the columns of `basis` (to round-off).
bool inSpan(const Eigen::MatrixXd& basis, const Eigen::VectorXd& v) {
  if (basis.cols() == 0)
    return v.norm() == 0.0;
  const Eigen::VectorXd coeff = basis.colPivHouseholderQr().solve(v);
  return (basis * coeff - v).norm() <= 1e-7 * v.norm();
}

Eigen::VectorXd direction(int n, std::initializer_list<std::pair<int, double>> entries) {
  Eigen::VectorXd v = Eigen::VectorXd::Zero(n);
  for (const auto& [i, value] : entries)
    v(i) = value;
  return v;
}

// The digest's numerical check (2.5, A001-9): Omega independent of R, L gives rank 5 for all
// three models, not the paper's 6.
TEST(Observability, IndependentGyroIncrementsGiveRankFiveForAllThreeModels) {
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    const auto segments = randomSegments(12, seed, SegmentKind::kIndependent, kD);
    EXPECT_EQ(analyseObservability(DrModelKind::kNineState, segments).rank, 5);
    EXPECT_EQ(analyseObservability(DrModelKind::kEightState, segments).rank, 5);
    EXPECT_EQ(analyseObservability(DrModelKind::kSevenState, segments).rank, 5);
  }
}

// The null space of the 9-state model is the paper's three directions (dx, dy, the common
// heading error) plus (S_R, S_L, dD) ~ (1, 1, D).
TEST(Observability, NineStateNullSpaceIsPositionCommonHeadingAndCommonScaleWithWheelbase) {
  const auto segments = randomSegments(12, 5, SegmentKind::kIndependent, kD);
  const ObservabilityReport r = analyseObservability(DrModelKind::kNineState, segments);
  ASSERT_EQ(r.null_space.cols(), 4);
  EXPECT_TRUE(inSpan(r.null_space, direction(9, {{0, 1.0}})));
  EXPECT_TRUE(inSpan(r.null_space, direction(9, {{1, 1.0}})));
  EXPECT_TRUE(inSpan(r.null_space, direction(9, {{2, 1.0}, {6, 1.0}})));
  EXPECT_TRUE(inSpan(r.null_space, direction(9, {{3, 1.0}, {4, 1.0}, {5, kD}})));
  // The readable basis prints the scale/wheelbase direction as S_R = S_L = 1, dD = D.
  bool found = false;
  for (Eigen::Index c = 0; c < r.null_space.cols(); ++c)
    found =
        found || (r.null_space.col(c) - direction(9, {{3, 1.0}, {4, 1.0}, {5, kD}})).norm() < 1e-9;
  EXPECT_TRUE(found);
}

// Structural, for any segments: (R(1+s) - L(1+s)) / (D(1+s)) = (R - L) / D.
TEST(Observability, CommonScaleWithWheelbaseIsInTheNullSpaceOfEveryTom) {
  for (SegmentKind kind : {SegmentKind::kIndependent, SegmentKind::kConsistent}) {
    for (std::uint64_t seed = 10; seed < 20; ++seed) {
      const auto segments = randomSegments(9, seed, kind, kD);
      EXPECT_LT((totalObservabilityMatrix(DrModelKind::kNineState, segments) *
                 direction(9, {{3, 1.0}, {4, 1.0}, {5, kD}}))
                    .norm(),
                1e-12);
      EXPECT_LT((totalObservabilityMatrix(DrModelKind::kEightState, segments) *
                 direction(8, {{3, 1.0}, {4, 1.0}, {5, kD}}))
                    .norm(),
                1e-12);
      EXPECT_LT((totalObservabilityMatrix(DrModelKind::kSevenState, segments) *
                 direction(7, {{1, 1.0}, {2, 1.0}, {3, kD}}))
                    .norm(),
                1e-12);
    }
  }
}

// The paper's rank 6 is out of reach: four (9-state), three (8) and two (7) null directions
// are structural, so the rank never exceeds 5, whatever the segments.
TEST(Observability, ThePapersRankSixIsNeverReached) {
  for (std::uint64_t seed = 100; seed < 130; ++seed) {
    for (int count : {9, 20, 40}) {
      const auto segments = randomSegments(count, seed, SegmentKind::kIndependent, kD);
      EXPECT_LE(analyseObservability(DrModelKind::kNineState, segments).rank, 5);
      EXPECT_LE(analyseObservability(DrModelKind::kEightState, segments).rank, 5);
      EXPECT_LE(analyseObservability(DrModelKind::kSevenState, segments).rank, 5);
    }
  }
}

// A real gyro sees the rotation the wheels make (Omega = (R - L) / D): then a common encoder
// scale error is also indistinguishable from a gyro scale error, and the rank drops to 4.
TEST(Observability, PhysicallyConsistentSegmentsAlsoHideTheGyroScaleAgainstTheCommonScale) {
  const auto segments = randomSegments(12, 8, SegmentKind::kConsistent, kD);
  const ObservabilityReport nine = analyseObservability(DrModelKind::kNineState, segments);
  EXPECT_EQ(nine.rank, 4);
  EXPECT_TRUE(inSpan(nine.null_space, direction(9, {{3, 1.0}, {4, 1.0}, {7, 1.0}})));
  EXPECT_TRUE(inSpan(nine.null_space, direction(9, {{3, 1.0}, {4, 1.0}, {5, kD}})));
  const ObservabilityReport eight = analyseObservability(DrModelKind::kEightState, segments);
  EXPECT_EQ(eight.rank, 4);
  EXPECT_TRUE(inSpan(eight.null_space, direction(8, {{3, 1.0}, {4, 1.0}, {6, 1.0}})));
  const ObservabilityReport seven = analyseObservability(DrModelKind::kSevenState, segments);
  EXPECT_EQ(seven.rank, 4);
  EXPECT_TRUE(inSpan(seven.null_space, direction(7, {{0, 1.0}, {4, 1.0}})));  // (17)'s null
  EXPECT_TRUE(inSpan(seven.null_space, direction(7, {{1, 1.0}, {2, 1.0}, {5, 1.0}})));
}

// What is observable: the differential scale S_R - S_L and the gyro bias are not in the null
// space (their variances converge in the loop experiment).
TEST(Observability, DifferentialScaleAndGyroBiasAreObservable) {
  const auto segments = randomSegments(12, 4, SegmentKind::kConsistent, kD);
  const ObservabilityReport r = analyseObservability(DrModelKind::kNineState, segments);
  // A state direction e is observable iff it has a component outside the null space; the
  // projection onto the null space's orthogonal complement must not vanish.
  const Eigen::MatrixXd q = r.null_space.householderQr().householderQ() *
                            Eigen::MatrixXd::Identity(9, r.null_space.cols());
  for (const Eigen::VectorXd& e : {direction(9, {{3, 1.0}, {4, -1.0}}), direction(9, {{8, 1.0}})}) {
    EXPECT_GT((e - q * (q.transpose() * e)).norm(), 0.1);
  }
}

TEST(Observability, BadInputThrows) {
  EXPECT_THROW(totalObservabilityMatrix(DrModelKind::kNineState, {}), std::invalid_argument);
  EXPECT_THROW(randomSegments(0, 1, SegmentKind::kConsistent), std::invalid_argument);
  EXPECT_THROW(randomSegments(3, 1, SegmentKind::kConsistent, -0.5), std::invalid_argument);
  EXPECT_THROW(analyseObservability(DrModelKind::kNineState,
                                    randomSegments(3, 1, SegmentKind::kConsistent), -1.0),
               std::invalid_argument);
  DrSegment bad;
  bad.wheelbase_m = 0.0;
  EXPECT_THROW(totalObservabilityMatrix(DrModelKind::kSevenState, {bad}), std::invalid_argument);
}

TEST(Observability, ReportNamesRankAndDirections) {
  const auto segments = randomSegments(12, 5, SegmentKind::kIndependent, kD);
  const std::string text = formatReport(DrModelKind::kNineState,
                                        analyseObservability(DrModelKind::kNineState, segments));
  EXPECT_NE(text.find("rank(TOM) = 5 of 9"), std::string::npos);
  EXPECT_NE(text.find("S_R=1 S_L=1 dD=0.5"), std::string::npos);
}

}  // namespace
}  // namespace irgs
