// Session recording (issue 6 item 2): the SQLite file round-trips every table, is in WAL mode,
// commits within the flush period while still open, survives a copy taken mid-write (what an
// unclean stop leaves), and refuses bad files with a clear reason.

#include "app/recording/session_recorder.hpp"
#include "app/recording/recording_reader.hpp"
#include "tests/app/recording/recording_pattern.hpp"
#include "tests/app/recording/recording_test_support.hpp"

#include <gtest/gtest.h>

#include <QFile>
#include <QSqlDatabase>
#include <QSqlQuery>
#include <QVariant>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <thread>

namespace irgs::recording {
namespace {

namespace fs = std::filesystem;
using comms::TapDirection;

using testing::pattern;

class SessionRecorderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    testing::ensureCoreApplication();
    dir_ = testing::makeTempDir("irgs-recorder");
    path_ = (dir_ / "session.irgsrec").string();
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  fs::path dir_;
  std::string path_;
};

TEST_F(SessionRecorderTest, RoundTripsFramesEventsTruthCommandsAndMeta) {
  {
    auto opened = SessionRecorder::create(path_, {{"robot", "thesis"}});
    ASSERT_TRUE(opened.recorder) << opened.error;
    const auto t0 = std::chrono::steady_clock::now();  // after the recorder's epoch
    SessionRecorder& rec = *opened.recorder;
    for (std::size_t i = 0; i < 100; ++i)
      rec.recordFrame(i % 3 == 0 ? TapDirection::kSent : TapDirection::kReceived,
                      t0 + std::chrono::milliseconds(10 * i), pattern(i));
    rec.recordEvent("warning", "Link lost: no heartbeat for 1.5 s");
    rec.recordTruth(1.0, -2.0, 0.5);
    rec.recordTruth(std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0);  // ignored
    rec.recordCommand("drive 0.200 0.000");
    rec.setMeta("map", "default.json");
    rec.flush();
    const RecorderStats stats = rec.stats();
    EXPECT_EQ(stats.frames, 100u);
    EXPECT_EQ(stats.events, 1u);
    EXPECT_EQ(stats.truth, 1u);
    EXPECT_EQ(stats.commands, 1u);
    EXPECT_TRUE(stats.last_error.empty()) << stats.last_error;
  }
  const LoadResult loaded = loadRecording(path_);
  ASSERT_TRUE(loaded.recording) << loaded.error;
  const Recording& r = *loaded.recording;
  ASSERT_EQ(r.frames.size(), 100u);
  for (std::size_t i = 0; i < r.frames.size(); ++i) {
    EXPECT_EQ(r.frames[i].bytes, pattern(i)) << i;
    EXPECT_EQ(r.frames[i].dir, i % 3 == 0 ? 1 : 0) << i;
    // The recorder's epoch is taken in create(), just before t0.
    EXPECT_NEAR(r.frames[i].t_s, 0.010 * static_cast<double>(i), 0.5) << i;
    if (i > 0) {
      EXPECT_NEAR(r.frames[i].t_s - r.frames[i - 1].t_s, 0.010, 1e-9) << i;
    }
  }
  EXPECT_EQ(r.receivedFrameCount(), 66u);
  ASSERT_EQ(r.events.size(), 1u);
  EXPECT_EQ(r.events[0].kind, "warning");
  EXPECT_EQ(r.events[0].text, "Link lost: no heartbeat for 1.5 s");
  ASSERT_EQ(r.truth.size(), 1u);
  EXPECT_EQ(r.truth[0].x_m, 1.0);
  EXPECT_EQ(r.truth[0].y_m, -2.0);
  EXPECT_EQ(r.truth[0].theta_rad, 0.5);
  ASSERT_EQ(r.commands.size(), 1u);
  EXPECT_EQ(r.commands[0].text, "drive 0.200 0.000");
  EXPECT_EQ(r.meta.at("format_version"), std::to_string(kFormatVersion));
  EXPECT_EQ(r.meta.at("robot"), "thesis");
  EXPECT_EQ(r.meta.at("map"), "default.json");
  EXPECT_FALSE(r.meta.at("created_utc").empty());
  EXPECT_GE(r.duration_s(), r.frames.back().t_s);
  EXPECT_TRUE(loaded.warnings.empty());
}

TEST_F(SessionRecorderTest, WritesInWalModeAndCommitsWithinTheFlushPeriodWhileOpen) {
  auto opened = SessionRecorder::create(path_, {}, RecorderConfig{.flush_period_s = 0.25});
  ASSERT_TRUE(opened.recorder) << opened.error;
  opened.recorder->recordFrame(TapDirection::kReceived, std::chrono::steady_clock::now(),
                               pattern(5));
  // No flush(): the writer commits on its own. Poll the file as another process would.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(1);
  std::size_t frames = 0;
  while (std::chrono::steady_clock::now() < deadline) {
    const LoadResult loaded = loadRecording(path_);
    ASSERT_TRUE(loaded.recording) << loaded.error;
    frames = loaded.recording->frames.size();
    if (frames == 1)
      break;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  EXPECT_EQ(frames, 1u) << "not committed within 1 s (flush period 0.25 s)";
  EXPECT_TRUE(fs::exists(path_ + "-wal")) << "no WAL file beside the open recording";
  {
    QSqlDatabase db = QSqlDatabase::addDatabase(QStringLiteral("QSQLITE"), QStringLiteral("wal"));
    db.setDatabaseName(QString::fromStdString(path_));
    ASSERT_TRUE(db.open());
    QSqlQuery q(db);
    ASSERT_TRUE(q.exec(QStringLiteral("PRAGMA journal_mode")) && q.next());
    EXPECT_EQ(q.value(0).toString(), QStringLiteral("wal"));
  }
  QSqlDatabase::removeDatabase(QStringLiteral("wal"));
}

TEST_F(SessionRecorderTest, ACopyTakenMidWriteOpensWithEveryCommittedRow) {
  // What an unclean stop leaves: the main file and its -wal, never checkpointed, no clean close.
  auto opened = SessionRecorder::create(path_, {});
  ASSERT_TRUE(opened.recorder) << opened.error;
  const auto t0 = std::chrono::steady_clock::now();
  for (std::size_t i = 0; i < 500; ++i)
    opened.recorder->recordFrame(TapDirection::kReceived, t0, pattern(i));
  opened.recorder->flush();
  const fs::path copy = dir_ / "crashed.irgsrec";
  fs::copy_file(path_, copy);
  ASSERT_TRUE(fs::exists(path_ + "-wal"));
  fs::copy_file(path_ + "-wal", copy.string() + "-wal");
  opened.recorder->recordFrame(TapDirection::kReceived, t0, pattern(999));  // after the "crash"
  const LoadResult loaded = loadRecording(copy.string());
  ASSERT_TRUE(loaded.recording) << loaded.error;
  ASSERT_EQ(loaded.recording->frames.size(), 500u);
  for (std::size_t i = 0; i < 500; ++i)
    EXPECT_EQ(loaded.recording->frames[i].bytes, pattern(i)) << i;
}

TEST_F(SessionRecorderTest, NeverOverwritesAnExistingFile) {
  std::ofstream(path_) << "precious";
  const auto opened = SessionRecorder::create(path_, {});
  EXPECT_FALSE(opened.recorder);
  EXPECT_NE(opened.error.find("already exists"), std::string::npos) << opened.error;
  std::ifstream in(path_);
  std::string text;
  in >> text;
  EXPECT_EQ(text, "precious");
}

TEST_F(SessionRecorderTest, NamesAMissingDirectory) {
  const auto opened = SessionRecorder::create((dir_ / "no" / "such.irgsrec").string(), {});
  EXPECT_FALSE(opened.recorder);
  EXPECT_NE(opened.error.find("does not exist"), std::string::npos) << opened.error;
}

TEST_F(SessionRecorderTest, RejectsAFlushPeriodAboveOneSecond) {
  EXPECT_THROW(SessionRecorder::create(path_, {}, RecorderConfig{.flush_period_s = 2.0}),
               std::invalid_argument);
  EXPECT_THROW(SessionRecorder::create(path_, {}, RecorderConfig{.flush_period_s = 0.0}),
               std::invalid_argument);
}

TEST_F(SessionRecorderTest, ATapOutlivingTheRecorderDoesNothing) {
  comms::FrameTap tap;
  {
    auto opened = SessionRecorder::create(path_, {});
    ASSERT_TRUE(opened.recorder);
    tap = opened.recorder->tap();
    const std::uint8_t byte = 7;
    tap(TapDirection::kReceived, std::chrono::steady_clock::now(), {&byte, 1});
  }
  const std::uint8_t byte = 8;
  tap(TapDirection::kReceived, std::chrono::steady_clock::now(), {&byte, 1});  // no crash
  const LoadResult loaded = loadRecording(path_);
  ASSERT_TRUE(loaded.recording) << loaded.error;
  ASSERT_EQ(loaded.recording->frames.size(), 1u);
  EXPECT_EQ(loaded.recording->frames[0].bytes, std::vector<std::uint8_t>{7});
}

TEST_F(SessionRecorderTest, TheReaderRejectsFilesThatAreNotRecordings) {
  EXPECT_NE(loadRecording((dir_ / "missing.irgsrec").string()).error.find("does not exist"),
            std::string::npos);
  const std::string text = (dir_ / "text.irgsrec").string();
  std::ofstream(text) << "this is not a database, it is a text file of some length\n";
  const LoadResult garbage = loadRecording(text);
  EXPECT_FALSE(garbage.recording);
  EXPECT_FALSE(garbage.error.empty());

  // A SQLite file from a newer IRGS.
  {
    auto opened = SessionRecorder::create(path_, {});
    ASSERT_TRUE(opened.recorder);
    opened.recorder->setMeta("format_version", "99");
  }
  const LoadResult newer = loadRecording(path_);
  EXPECT_FALSE(newer.recording);
  EXPECT_NE(newer.error.find("format 99"), std::string::npos) << newer.error;
}

TEST_F(SessionRecorderTest, TheReaderSkipsUnusableRowsWithAWarning) {
  {
    auto opened = SessionRecorder::create(path_, {});
    ASSERT_TRUE(opened.recorder);
    opened.recorder->recordFrame(TapDirection::kReceived, std::chrono::steady_clock::now(),
                                 pattern(1));
  }
  {
    QSqlDatabase db = QSqlDatabase::addDatabase(QStringLiteral("QSQLITE"), QStringLiteral("bad"));
    db.setDatabaseName(QString::fromStdString(path_));
    ASSERT_TRUE(db.open());
    QSqlQuery q(db);
    ASSERT_TRUE(q.exec(QStringLiteral("INSERT INTO frames(t, dir, bytes) VALUES(-1, 0, x'01')")));
    ASSERT_TRUE(q.exec(QStringLiteral("INSERT INTO frames(t, dir, bytes) VALUES(1, 7, x'01')")));
    ASSERT_TRUE(q.exec(QStringLiteral("INSERT INTO frames(t, dir, bytes) VALUES(1, 0, x'')")));
    ASSERT_TRUE(q.exec(QStringLiteral("INSERT INTO events(t, kind, text) VALUES('x', 'i', 't')")));
  }
  QSqlDatabase::removeDatabase(QStringLiteral("bad"));
  const LoadResult loaded = loadRecording(path_);
  ASSERT_TRUE(loaded.recording) << loaded.error;
  EXPECT_EQ(loaded.recording->frames.size(), 1u);
  EXPECT_TRUE(loaded.recording->events.empty());
  ASSERT_EQ(loaded.warnings.size(), 1u);
  EXPECT_NE(loaded.warnings[0].find("skipped 4"), std::string::npos) << loaded.warnings[0];
}

}  // namespace
}  // namespace irgs::recording
