#include "widgets/canvas/label_placement.hpp"

#include <gtest/gtest.h>

namespace irgs::widgets {
namespace {

const QRectF kBox(0, 0, 20, 10);

TEST(LabelPlacement, GoesAboveRightOfAFreePoint) {
  const QRectF r = placeLabel(kBox, QPointF(100, 100), {});
  EXPECT_EQ(r, QRectF(106, 84, 20, 10));
}

TEST(LabelPlacement, APointOnTopOfAnotherGetsItsLabelWhereNeitherCoversTheOther) {
  // Map building drops index 20 where index 3 already is (the loop's closure): "3" and "20"
  // printed as "320".
  std::vector<QRectF> taken{placeLabel(kBox, QPointF(100, 100), {})};
  const QRectF second = placeLabel(kBox, QPointF(102, 101), taken);
  EXPECT_FALSE(second.intersects(taken.front()));
  EXPECT_EQ(second.topLeft(), QPointF(108, 107));  // below right, the next choice
  taken.push_back(second);
  const QRectF third = placeLabel(kBox, QPointF(101, 100), taken);
  EXPECT_FALSE(third.intersects(taken[0]));
  EXPECT_FALSE(third.intersects(taken[1]));
  EXPECT_LT(third.right(), 101.0);  // to the left now
}

TEST(LabelPlacement, WhenEveryPlaceIsTakenTheLeastCoveredOneWins) {
  const QPointF at(100, 100);
  std::vector<QRectF> taken{QRectF(0, 0, 200, 200)};  // covers all four fully
  taken.push_back(QRectF(106, 84, 20, 10));           // above right twice over
  const QRectF r = placeLabel(kBox, at, taken);
  EXPECT_NE(r.topLeft(), QPointF(106, 84));
}

}  // namespace
}  // namespace irgs::widgets
