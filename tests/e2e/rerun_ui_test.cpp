// File > Re-run with Parameters... offscreen (issue 6 item 3): the menu entry, the dialog
// prefilled with the recording's parameters (a refused value keeps it open), the worker run, the
// side-by-side window with both maps, both trajectories and the metrics table, and a cancelled
// dialog that starts nothing. Also: destroying the main window while a replay is open (the
// recording UI destructor used to crash there).

#include "app/gui/rerun_ui.hpp"

#include <gtest/gtest.h>

#include <QAction>
#include <QDir>
#include <QLabel>
#include <QMenu>
#include <QMenuBar>
#include <QSignalSpy>
#include <QTableWidget>
#include <QTimer>
#include <chrono>

#include "app/gui/link_ui.hpp"
#include "app/gui/recording_ui.hpp"
#include "app/gui/rerun_dialog.hpp"
#include "app/recording/recording_reader.hpp"
#include "app/recording/session_recorder.hpp"
#include "comms/mavlink/frame_encoder.hpp"
#include "comms/mavlink/messages.hpp"
#include "tests/e2e/main_window_fixture.hpp"
#include "widgets/replay/rerun_compare_view.hpp"

namespace irgs::gui {
namespace {

namespace mav = comms::mavlink;

constexpr int kPoses = 80;

// The thesis robot driving an arc with all sonars echoing, recorded as received bytes; the
// session mapped it at 2 cm (meta param.grid_resolution_m).
void writeRobotRecording(const QString& path, std::size_t sonars) {
  auto opened = recording::SessionRecorder::create(
      path.toStdString(), {{"robot", "thesis_robot"}, {"param.grid_resolution_m", "0.02"}});
  ASSERT_TRUE(opened.recorder) << opened.error;
  mav::FrameEncoder encoder(1, 1);
  const auto t0 = std::chrono::steady_clock::now();
  double x = 0.0, y = 0.0, theta = 0.0;
  for (int i = 0; i < kPoses; ++i) {
    const auto t = t0 + std::chrono::milliseconds(50 * i);
    if (i % 20 == 0) {
      mav::Heartbeat hb;
      hb.type = static_cast<std::uint8_t>(mav::MavType::kGroundRover);
      opened.recorder->recordFrame(comms::TapDirection::kReceived, t, encoder.encode(hb).view());
    }
    const auto boot_ms = static_cast<std::uint32_t>(1000 + 50 * i);
    mav::IrgsPose2d pose;
    pose.time_boot_ms = boot_ms;
    pose.x = static_cast<float>(x);
    pose.y = static_cast<float>(y);
    pose.theta = static_cast<float>(theta);
    opened.recorder->recordFrame(comms::TapDirection::kReceived, t, encoder.encode(pose).view());
    mav::IrgsSonarScan scan;
    scan.time_boot_ms = boot_ms;
    scan.count = static_cast<std::uint8_t>(sonars);
    scan.fired = static_cast<std::uint16_t>((1u << sonars) - 1);
    for (std::size_t s = 0; s < sonars; ++s)
      scan.range[s] = static_cast<std::uint16_t>(700 + 15 * ((i + static_cast<int>(s)) % 30));
    opened.recorder->recordFrame(comms::TapDirection::kReceived, t + std::chrono::milliseconds(2),
                                 encoder.encode(scan).view());
    x += 0.015 * std::cos(theta);
    y += 0.015 * std::sin(theta);
    theta += 0.02;
  }
}

class RerunUiTest : public test::MainWindowFixture {
 protected:
  void SetUp() override {
    openWindow(test::squareRoom(2.5));
    recording_ = new RecordingUi(*session_, window_->linkUi().controller(), *window_);
    rerun_ = new RerunUi(*session_, *window_, recording_->openRecordingAction());
    path_ = dir_.filePath(QStringLiteral("robot.irgsrec"));
    writeRobotRecording(path_, session_->profile().sonars.size());
    rerun_->setRecordingChooser([this] { return path_; });
  }
  void TearDown() override {
    window_.reset();
    session_.reset();
  }

  RecordingUi* recording_ = nullptr;
  RerunUi* rerun_ = nullptr;
  QString path_;
};

TEST_F(RerunUiTest, TheFileMenuOffersRerunAfterOpenRecording) {
  QMenu* file = nullptr;
  for (QAction* top : window_->menuBar()->actions()) {
    if (top->menu() != nullptr && top->menu()->title() == QStringLiteral("&File"))
      file = top->menu();
  }
  ASSERT_NE(file, nullptr);
  const QList<QAction*> actions = file->actions();
  const qsizetype open = actions.indexOf(recording_->openRecordingAction());
  ASSERT_GE(open, 0);
  ASSERT_LT(open + 1, actions.size());
  EXPECT_EQ(actions[open + 1], rerun_->action());
  EXPECT_TRUE(rerun_->action()->text().contains(QStringLiteral("Re-run")));
}

TEST_F(RerunUiTest, TheDialogStartsAWorkerRunAndTheWindowComparesBothRuns) {
  bool refused_kept_open = false;
  QString prefilled;
  rerun_->setDialogHook([&](RerunDialog& dialog) {
    prefilled = dialog.value("grid_resolution_m");
    QTimer::singleShot(0, &dialog, [&dialog, &refused_kept_open] {
      dialog.setValue("sonar_valid_distance_m", QStringLiteral("far"));
      dialog.accept();  // refused: the reason shows, the dialog stays
      refused_kept_open = dialog.isVisible() && dialog.error().contains(QStringLiteral("far"));
      dialog.setValue("sonar_valid_distance_m", QStringLiteral("0.5"));
      dialog.setValue("grid_resolution_m", QStringLiteral("0.01"));
      dialog.accept();
    });
  });
  QSignalSpy finished(rerun_, &RerunUi::finished);
  rerun_->action()->trigger();
  EXPECT_EQ(prefilled, QStringLiteral("0.02"));  // the recording's parameter, not the default
  EXPECT_TRUE(refused_kept_open);
  ASSERT_TRUE(finished.count() > 0 || finished.wait(30000)) << "the re-run never finished";
  EXPECT_TRUE(finished.first().at(0).toBool()) << finished.first().at(1).toString().toStdString();
  EXPECT_FALSE(rerun_->running());

  const recording::RerunResult* r = rerun_->result();
  ASSERT_NE(r, nullptr);
  EXPECT_EQ(r->samples, static_cast<std::size_t>(kPoses));
  EXPECT_EQ(r->recorded.grid.resolution_m(), 0.02);
  EXPECT_EQ(r->rerun.grid.resolution_m(), 0.01);
  EXPECT_EQ(r->rerun.parameters.validDistance(), 0.5);
  EXPECT_EQ(r->metrics.grid.candidate_occupied, 0u);  // every echo is beyond 0.5 m
  EXPECT_LT(r->metrics.grid.agreement, 0.9);
  EXPECT_EQ(r->metrics.pose.max_position_m, 0.0);

  ASSERT_NE(rerun_->compareWindow(), nullptr);
  EXPECT_TRUE(rerun_->compareWindow()->isVisible());
  widgets::RerunCompareView* view = rerun_->compareView();
  ASSERT_NE(view, nullptr);
  ASSERT_EQ(view->recordedCanvas().tracks().size(), 2u);  // own solid, the other dashed
  EXPECT_EQ(view->recordedCanvas().tracks()[0].points.size(), static_cast<std::size_t>(kPoses));
  EXPECT_EQ(view->recordedCanvas().tracks()[1].style, Qt::DashLine);
  // The two views move together.
  view->recordedCanvas().setView({1.0, 0.5}, 150.0);
  EXPECT_NEAR(view->rerunCanvas().pixelsPerMetre(), 150.0, 1e-9);
  EXPECT_NEAR(view->rerunCanvas().viewCentre().x(), 1.0, 1e-9);
  const QTableWidget& table = view->metricsTable();
  EXPECT_EQ(table.rowCount(), static_cast<int>(rerunMetricRows(*r).size()));
  bool changed_listed = false;
  for (int row = 0; row < table.rowCount(); ++row) {
    if (table.item(row, 0)->text() == QStringLiteral("Changed parameters"))
      changed_listed =
          table.item(row, 3)->text().contains(QStringLiteral("sonar_valid_distance_m"));
  }
  EXPECT_TRUE(changed_listed);

  // The files irgs-rerun writes, from the window's result.
  const QString out = dir_.filePath(QStringLiteral("out"));
  EXPECT_EQ(rerun_->saveOutputs(out), QString());
  EXPECT_TRUE(QFile::exists(out + QStringLiteral("/metrics.json")));
  EXPECT_TRUE(QFile::exists(out + QStringLiteral("/recorded_map.png")));
}

TEST_F(RerunUiTest, ACancelledDialogStartsNothingAndARecordingWithoutSamplesIsRefused) {
  rerun_->setDialogHook(
      [](RerunDialog& dialog) { QTimer::singleShot(0, &dialog, [&dialog] { dialog.reject(); }); });
  EXPECT_EQ(rerun_->start(path_), QString());
  EXPECT_FALSE(rerun_->running());
  EXPECT_EQ(rerun_->result(), nullptr);

  // A simulator session stopped before its first tick: no sample, so no received bytes.
  const QString sim = dir_.filePath(QStringLiteral("sim.irgsrec"));
  ASSERT_EQ(recording_->startRecording(sim), QString());
  recording_->stopRecording();
  EXPECT_TRUE(rerun_->start(sim).contains(QStringLiteral("no received link bytes")));
}

TEST_F(RerunUiTest, RecordingsCarryTheMappingParametersInForceAndTheirChanges) {
  const QString file = dir_.filePath(QStringLiteral("params.irgsrec"));
  recording_->setRobotFile(QStringLiteral("/some/where/thesis_robot.json"));
  ASSERT_EQ(recording_->startRecording(file), QString());
  session_->setMappingParameters(0.02, 1.5);
  recording_->stopRecording();
  const recording::LoadResult loaded = recording::loadRecording(file.toStdString());
  ASSERT_TRUE(loaded.recording) << loaded.error;
  const auto& meta = loaded.recording->meta;
  EXPECT_EQ(meta.at("robot_file"), "/some/where/thesis_robot.json");
  EXPECT_EQ(meta.at("param.grid_resolution_m"), "0.02");
  EXPECT_EQ(meta.at("param.sonar_valid_distance_m"), "1.5");
  const recording::RerunParameters recorded = recording::recordedRerunParameters(meta);
  EXPECT_EQ(recorded.grid_resolution_m, 0.02);
  EXPECT_EQ(recorded.validDistance(), 1.5);
  bool event = false;
  for (const recording::RecordedEvent& e : loaded.recording->events)
    event = event || e.text.find("Mapping parameters: grid_resolution_m=0.02") == 0;
  EXPECT_TRUE(event);
}

TEST_F(RerunUiTest, DestroyingTheWindowDuringAReplayAndWithARerunOpenIsSafe) {
  QSignalSpy finished(rerun_, &RerunUi::finished);
  ASSERT_EQ(rerun_->start(path_, recording::RerunParameters{}), QString());
  ASSERT_TRUE(finished.wait(30000));
  ASSERT_NE(rerun_->compareWindow(), nullptr);
  ASSERT_EQ(recording_->openReplay(path_, 1.0), QString());
  ASSERT_TRUE(recording_->replaying());
  session_->tick(0.05);
  window_.reset();  // RecordingUi and RerunUi go with it; must not crash
  session_->tick(0.05);
  SUCCEED();
}

}  // namespace
}  // namespace irgs::gui
