// The plots' MAVLink branch in the main window, offscreen: against irgs-robot over a pty, every
// numeric field of every message the robot sent (decoded here from the link's own received
// bytes) is in the field browser with its XML unit, and a field dragged onto a panel plots
// exactly the values of its frames at their robot time stamps, on the samples' time axis. A
// replayed recording feeds the same branch (replay is a link).

#include <gtest/gtest.h>

#include <QMimeData>
#include <QSignalSpy>
#include <QTemporaryDir>
#include <QTest>
#include <QTreeWidgetItem>
#include <chrono>
#include <cmath>
#include <map>
#include <mutex>
#include <set>
#include <vector>

#include "app/gui/link_controller.hpp"
#include "app/gui/link_ui.hpp"
#include "app/gui/main_window.hpp"
#include "app/gui/plots_controller.hpp"
#include "app/gui/recording_ui.hpp"
#include "app/gui/session_controller.hpp"
#include "app/recording/session_recorder.hpp"
#include "comms/mavlink/field_info.hpp"
#include "comms/mavlink/frame_decoder.hpp"
#include "comms/mavlink/frame_encoder.hpp"
#include "comms/mavlink/messages.hpp"
#include "comms/robot/message_sampler.hpp"
#include "tests/e2e/child_process.hpp"
#include "tests/e2e/main_window_fixture.hpp"
#include "widgets/plots/field_browser.hpp"
#include "widgets/plots/plot_data_hub.hpp"
#include "widgets/plots/plot_panel.hpp"
#include "widgets/plots/plots_dock.hpp"

namespace irgs::gui {
namespace {

namespace mav = comms::mavlink;

constexpr int kTimeout_ms = 60000;  // a loaded 2-core machine

// What the link received, copied on the io thread by the frame tap.
struct Received {
  std::mutex mutex;
  std::vector<std::uint8_t> bytes;
  std::vector<mav::Frame> frames() {
    std::vector<std::uint8_t> copy;
    {
      const std::lock_guard lock(mutex);
      copy = bytes;
    }
    mav::FrameDecoder decoder;
    const mav::DecodeResult result = decoder.feed(copy);
    return {result.frames.begin(), result.frames.end()};
  }
};

bool dropOn(QWidget& target, const QMimeData& mime) {
  const QPoint at(target.width() / 2, target.height() / 2);
  QDragEnterEvent enter(at, Qt::CopyAction, &mime, Qt::LeftButton, Qt::NoModifier);
  QCoreApplication::sendEvent(&target, &enter);
  if (!enter.isAccepted())
    return false;
  QDropEvent drop(QPointF(at), Qt::CopyAction, &mime, Qt::LeftButton, Qt::NoModifier);
  QCoreApplication::sendEvent(&target, &drop);
  return drop.isAccepted();
}

// The browser key of a frame's field, as PlotsController names it.
QString keyOf(const mav::Frame& frame, const mav::MessageFields& message, std::size_t index) {
  comms::MessageSample sample;
  sample.message = &message;
  if (const auto instance = mav::instanceField(message))
    sample.instance = static_cast<std::uint32_t>(mav::readField(message.fields[*instance], frame));
  return PlotsController::mavlinkKey(sample, index);
}

// Drags `key` from the browser onto `panel` exactly as a mouse drag would deliver it.
bool dragToPanel(widgets::FieldBrowser& browser, widgets::PlotPanel& panel, const QString& key) {
  QTreeWidgetItem* item = browser.itemFor(key);
  if (item == nullptr)
    return false;
  std::unique_ptr<QMimeData> mime(browser.mimeData({item}));
  return mime != nullptr && dropOn(panel, *mime);
}

// How many of `series`' samples are a frame's (time stamp, value) under the best single clock
// offset (robot time -> plot time): the plot must use the frames' own time stamps.
std::size_t matchedSamples(const widgets::PlotSeries& series,
                           const std::map<std::int64_t, double>& frame_value_by_ms) {
  std::size_t best = 0;
  for (const auto& [ms0, v0] : frame_value_by_ms) {
    if (v0 != series.oldest().value)
      continue;
    const double offset_s = series.oldest().time_s - static_cast<double>(ms0) * 1e-3;
    std::size_t matched = 0;
    series.forEach(0, series.size(), [&](const widgets::PlotSample& s) {
      const auto ms = std::llround((s.time_s - offset_s) * 1000.0);
      const auto it = frame_value_by_ms.find(ms);
      if (it != frame_value_by_ms.end() && it->second == s.value &&
          std::abs((s.time_s - offset_s) * 1000.0 - static_cast<double>(ms)) < 1e-3)
        ++matched;
    });
    best = std::max(best, matched);
  }
  return best;
}

class PlotsMavlinkTest : public test::MainWindowFixture {
 protected:
  void SetUp() override {
    openWindow(test::squareRoom());
    window_->resize(1200, 800);
    window_->show();
    ASSERT_TRUE(QTest::qWaitForWindowExposed(window_.get()));
    window_->plots().dock().show();
  }
  void TearDown() override {
    window_.reset();
    session_.reset();  // the linked robot (and its io thread) goes with the session
    robot_.reset();
  }

  PlotsController& plots() const { return window_->plots(); }
  widgets::FieldBrowser& browser() const { return plots().plots().browser(); }

  std::unique_ptr<irgs::test::ChildProcess> robot_;
};

TEST_F(PlotsMavlinkTest, EveryFieldOfEveryRobotMessageIsBrowsableAndADraggedOnePlotsItsFrames) {
  const std::string pty_link = dir_.filePath(QStringLiteral("robot")).toStdString();
  robot_ = std::make_unique<irgs::test::ChildProcess>(std::vector<std::string>{
      IRGS_ROBOT_EXE, "--link", pty_link, "--baud", "115200", "--seed", "5"});
  const auto pts = robot_->readLine(irgs::test::Clock::now() + std::chrono::seconds(30));
  ASSERT_TRUE(pts && pts->rfind("/dev/pts/", 0) == 0) << "irgs-robot printed no pty path";

  auto received = std::make_shared<Received>();
  LinkController& link = window_->linkUi().controller();
  link.setFrameTap([received](comms::TapDirection direction, std::chrono::steady_clock::time_point,
                              std::span<const std::uint8_t> bytes) {
    if (direction != comms::TapDirection::kReceived)
      return;
    const std::lock_guard lock(received->mutex);
    received->bytes.insert(received->bytes.end(), bytes.begin(), bytes.end());
  });
  session_->start();
  ASSERT_EQ(link.connectTo(QString::fromStdString("serial://" + pty_link + "?baud=115200")),
            QString());
  ASSERT_TRUE(QTest::qWaitFor([&] { return link.rates().samples > 20; }, kTimeout_ms));
  session_->drive(0.15, 0.5);  // values that change
  ASSERT_TRUE(QTest::qWaitFor([&] { return link.rates().samples > 100; }, kTimeout_ms));
  session_->stopRobot();

  // Every stream the robot sent so far; the GUI takes them within a few ticks.
  const std::vector<mav::Frame> frames = received->frames();
  std::map<QString, const mav::MessageFields*> expected;  // key -> its message's table
  std::map<QString, std::string> units;
  std::set<std::string> messages;
  for (const mav::Frame& frame : frames) {
    const mav::MessageFields* table = mav::findMessageFields(frame.message_id);
    ASSERT_NE(table, nullptr) << "a message without a field table: " << frame.message_id;
    messages.insert(std::string(table->name));
    for (std::size_t i = 0; i < table->fields.size(); ++i) {
      const QString key = keyOf(frame, *table, i);
      expected[key] = table;
      units[key] = std::string(table->fields[i].unit);
    }
  }
  EXPECT_GE(messages.size(), 8u);  // heartbeat, status, pose, attitude, odometry, sonar, ...
  ASSERT_TRUE(QTest::qWaitFor(
      [&] {
        return std::all_of(expected.begin(), expected.end(),
                           [&](const auto& e) { return plots().hub().contains(e.first); });
      },
      10000));
  std::size_t checked = 0;
  for (const auto& [key, table] : expected) {
    QTreeWidgetItem* item = browser().itemFor(key);
    ASSERT_NE(item, nullptr) << key.toStdString();
    EXPECT_EQ(item->text(1).toStdString(), units[key]) << key.toStdString();
    // message > field (> instance > field for DISTANCE_SENSOR): the branch is "MAVLink".
    QTreeWidgetItem* top = item;
    while (top->parent() != nullptr)
      top = top->parent();
    EXPECT_EQ(top->text(0), QStringLiteral("MAVLink"));
    ++checked;
  }
  EXPECT_GE(checked, 100u);
  RecordProperty("messages", static_cast<int>(messages.size()));
  RecordProperty("fields", static_cast<int>(checked));
  EXPECT_NE(browser().itemFor(QStringLiteral("MAVLink/DISTANCE_SENSOR/id 0/current_distance")),
            nullptr);
  EXPECT_EQ(browser().itemFor(QStringLiteral("MAVLink/LOCAL_POSITION_NED/x"))->text(1),
            QStringLiteral("m"));

  // Drag LOCAL_POSITION_NED x onto the first panel: it plots the frames' x at their time stamps.
  const QString key = QStringLiteral("MAVLink/LOCAL_POSITION_NED/x");
  widgets::PlotsDock& dock = plots().plots();
  ASSERT_TRUE(dragToPanel(browser(), dock.panel(0), key));
  ASSERT_EQ(dock.panel(0).traces().size(), 1u);
  QTest::qWait(500);
  dock.refreshNow();
  const widgets::PlotSeries* series = plots().hub().series(key);
  ASSERT_NE(series, nullptr);
  std::map<std::int64_t, double> x_by_ms;
  std::size_t local_positions = 0;
  for (const mav::Frame& frame : received->frames()) {
    if (const auto lp = frame.as<mav::LocalPositionNed>()) {
      x_by_ms[lp->time_boot_ms] = static_cast<double>(lp->x);
      ++local_positions;
    }
  }
  ASSERT_GE(series->size(), 60u);
  // 20 Hz is under the 25 Hz per-stream limit: every frame taken so far is plotted.
  EXPECT_EQ(matchedSamples(*series, x_by_ms), series->size());
  EXPECT_GE(series->size() + 20, local_positions);  // the newest few may still be on their way
  // The panel shows them: its visible min/max are the series' over the visible window.
  const auto [t0, t1] = dock.panel(0).visibleTime();
  const auto shown = dock.panel(0).visibleRange(key);
  const auto range = series->range(t0, t1);
  ASSERT_TRUE(shown && range);
  EXPECT_DOUBLE_EQ(shown->min, range->min);
  EXPECT_DOUBLE_EQ(shown->max, range->max);
  EXPECT_GT(range->max - range->min, 0.05) << "the robot drove";

  // On the samples' time axis: the odometry x the session plotted at a sample's time is the
  // LOCAL_POSITION_NED x of that time stamp.
  const widgets::PlotSeries* odometry =
      plots().hub().series(QStringLiteral("Telemetry/Odometry pose/x"));
  ASSERT_NE(odometry, nullptr);
  std::size_t same_time = 0;
  // After the first time: the session shows its start pose before the link's first sample
  // arrives (SessionController::installRobot), at that sample's time.
  const double start_s = odometry->oldest().time_s;
  odometry->forEach(0, odometry->size(), [&](const widgets::PlotSample& s) {
    if (s.time_s == start_s)
      return;
    const std::size_t i = series->lowerBound(s.time_s - 1e-9);
    if (i < series->size() && std::abs(series->at(i).time_s - s.time_s) < 1e-6) {
      EXPECT_EQ(series->at(i).value, s.value) << "at " << s.time_s;
      ++same_time;
    }
  });
  EXPECT_GE(same_time, 20u);
  RecordProperty("plotted", static_cast<int>(series->size()));
  RecordProperty("frames", static_cast<int>(local_positions));
  RecordProperty("same_time", static_cast<int>(same_time));
}

TEST_F(PlotsMavlinkTest, AReplayedRecordingFeedsTheMavlinkBranch) {
  auto* recording = new RecordingUi(*session_, window_->linkUi().controller(), *window_);
  const QString file = dir_.filePath(QStringLiteral("robot.irgsrec"));
  constexpr int kPoses = 40;
  std::map<std::int64_t, double> x_by_ms;
  {
    auto opened = recording::SessionRecorder::create(file.toStdString(), {});
    ASSERT_TRUE(opened.recorder) << opened.error;
    mav::FrameEncoder encoder(1, 1);
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < kPoses; ++i) {
      const auto t = t0 + std::chrono::milliseconds(50 * i);
      if (i % 20 == 0) {
        mav::Heartbeat hb;
        hb.type = static_cast<std::uint8_t>(mav::MavType::kGroundRover);
        opened.recorder->recordFrame(comms::TapDirection::kReceived, t, encoder.encode(hb).view());
      }
      mav::IrgsPose2d pose;
      pose.time_boot_ms = static_cast<std::uint32_t>(1000 + 50 * i);
      pose.x = 0.0625f * static_cast<float>(i);
      x_by_ms[pose.time_boot_ms] = static_cast<double>(pose.x);
      opened.recorder->recordFrame(comms::TapDirection::kReceived, t, encoder.encode(pose).view());
    }
  }
  ASSERT_EQ(recording->openReplay(file, 4.0), QString());
  QSignalSpy drained(recording, &RecordingUi::replayDrained);
  session_->start();
  ASSERT_TRUE(drained.wait(20000)) << "the replay never drained";
  QTest::qWait(200);
  const QString key = QStringLiteral("MAVLink/IRGS_POSE_2D/x");
  EXPECT_NE(browser().itemFor(key), nullptr);
  EXPECT_NE(browser().itemFor(QStringLiteral("MAVLink/HEARTBEAT/type")), nullptr);
  const widgets::PlotSeries* series = plots().hub().series(key);
  ASSERT_NE(series, nullptr);
  // At x4 the stream arrives at 80 Hz and is thinned to 25 Hz after a burst of 8 (how many
  // pass depends on how the machine paced the replay); each kept value is at its own time.
  EXPECT_GE(series->size(), 8u);
  EXPECT_LE(series->size(), static_cast<std::size_t>(kPoses));
  EXPECT_EQ(matchedSamples(*series, x_by_ms), series->size());
  recording->closeReplay();
}

}  // namespace
}  // namespace irgs::gui
