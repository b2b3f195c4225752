#pragma once
// The numeric fields of a telemetry sample and of an estimator step, as plot fields (SI units,
// angles in radians; a panel converts for display). Keys are grouped by source so the field
// browser shows a tree: "Telemetry/...", "Estimator/...".

#include <QString>
#include <vector>

#include "core/estimation/estimator_runner.hpp"
#include "core/robot/telemetry.hpp"
#include "widgets/plots/plot_data_hub.hpp"

namespace irgs::widgets {

// Every numeric field of `sample`: poses, velocity, encoder ticks, each sonar's range (only
// the sonars that fired in this sample), proximity, gyro, contact. Optional parts appear only
// when present (true pose in simulator mode, gyro when fitted).
std::vector<PlotFieldValue> telemetryPlotFields(const TelemetrySample& sample);
// The estimator's belief: estimate, 1-sigma from the covariance, dead reckoning, and the error
// against truth and NEES when truth is known. `name` is the estimator's display name.
std::vector<PlotFieldValue> estimatorPlotFields(const EstimatorStep& step);

}  // namespace irgs::widgets
