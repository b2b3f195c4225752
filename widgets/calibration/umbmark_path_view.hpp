#pragma once
// The simulated UMBmark runs drawn in the start frame: the true paths (solid) and what the
// odometry believed (dashed), clockwise runs blue, counter-clockwise red, corrected runs green.
// The square the robot meant to drive is grey. Paint only; the data is set from outside.

#include <QWidget>
#include <vector>

#include "core/calibration/umbmark_run.hpp"

namespace irgs::widgets {

class UmbmarkPathView : public QWidget {
  Q_OBJECT

 public:
  explicit UmbmarkPathView(QWidget* parent = nullptr);

  // `before`: the runs on the uncalibrated odometry; `after`: the verification runs (may be
  // empty). Only the first run of each direction is drawn (the others overlap it).
  void setTrials(std::vector<UmbmarkTrial> before, std::vector<UmbmarkTrial> after, double side_m);
  void clear();
  QSize sizeHint() const override { return {360, 360}; }

 protected:
  void paintEvent(QPaintEvent* event) override;

 private:
  std::vector<UmbmarkTrial> before_;
  std::vector<UmbmarkTrial> after_;
  double side_m_ = 4.0;
};

}  // namespace irgs::widgets
