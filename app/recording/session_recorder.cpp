#include "app/recording/session_recorder.hpp"

#include <QDateTime>
#include <QDir>
#include <QFileInfo>
#include <QSqlDatabase>
#include <QSqlError>
#include <QSqlQuery>
#include <QString>
#include <QVariant>

#include <atomic>
#include <cmath>
#include <condition_variable>
#include <future>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <utility>
#include <vector>

namespace irgs::recording {

namespace {

struct Batch {
  std::vector<RecordedFrame> frames;
  std::vector<RecordedEvent> events;
  std::vector<RecordedTruth> truth;
  std::vector<RecordedCommand> commands;
  std::vector<std::pair<std::string, std::string>> meta;

  std::size_t rows() const {
    return frames.size() + events.size() + truth.size() + commands.size() + meta.size();
  }
};

QString qs(const std::string& s) {
  return QString::fromStdString(s);
}

std::string sqlError(const QString& what, const QSqlError& error) {
  return (what + QStringLiteral(": ") + error.text()).toStdString();
}

const char* const kSchema[] = {
    "CREATE TABLE IF NOT EXISTS meta(key TEXT PRIMARY KEY, value TEXT NOT NULL)",
    "CREATE TABLE IF NOT EXISTS frames(id INTEGER PRIMARY KEY, t REAL NOT NULL, "
    "dir INTEGER NOT NULL, bytes BLOB NOT NULL)",
    "CREATE TABLE IF NOT EXISTS events(id INTEGER PRIMARY KEY, t REAL NOT NULL, "
    "kind TEXT NOT NULL, text TEXT NOT NULL)",
    "CREATE TABLE IF NOT EXISTS truth(id INTEGER PRIMARY KEY, t REAL NOT NULL, x REAL NOT NULL, "
    "y REAL NOT NULL, theta REAL NOT NULL)",
    "CREATE TABLE IF NOT EXISTS commands(id INTEGER PRIMARY KEY, t REAL NOT NULL, "
    "text TEXT NOT NULL)",
};

std::atomic<std::uint64_t> g_connection_counter{0};

}  // namespace

struct SessionRecorder::Shared {
  std::chrono::steady_clock::time_point epoch = std::chrono::steady_clock::now();
  RecorderConfig config;
  std::string path;

  mutable std::mutex mutex;  // guards everything below
  std::condition_variable wake;
  std::condition_variable committed;
  Batch pending;
  bool stop = false;
  bool closed = false;  // the recorder is gone: taps do nothing
  std::uint64_t enqueued = 0;
  std::uint64_t done = 0;  // rows of `enqueued` written (or failed)
  bool flush_now = false;
  RecorderStats stats;
  std::thread writer;

  double seconds(std::chrono::steady_clock::time_point time) const {
    return std::chrono::duration<double>(time - epoch).count();
  }

  template <class F>
  void enqueue(F&& add) {
    const std::lock_guard lock(mutex);
    if (closed)
      return;
    if (pending.rows() >= config.max_queued_rows) {
      ++stats.dropped_rows;
      return;
    }
    add(pending);
    ++enqueued;
  }

  // ---- writer thread ----
  void run(std::promise<std::string> opened, std::map<std::string, std::string> meta) {
    const QString name = QStringLiteral("irgs_recorder_%1").arg(g_connection_counter.fetch_add(1));
    {
      QSqlDatabase db = QSqlDatabase::addDatabase(QStringLiteral("QSQLITE"), name);
      const std::string error = openDatabase(db, meta);
      const bool ok = error.empty();
      opened.set_value(error);
      if (ok)
        loop(db);
      db.close();
    }
    QSqlDatabase::removeDatabase(name);
  }

  std::string openDatabase(QSqlDatabase& db, const std::map<std::string, std::string>& meta) {
    if (!db.isValid())
      return "the Qt SQLite driver (libqt6sql6-sqlite) is not installed";
    db.setDatabaseName(qs(path));
    if (!db.open())
      return sqlError(QStringLiteral("cannot create ") + qs(path), db.lastError());
    QSqlQuery q(db);
    // WAL: readers (replay of a live file) never block the writer, and a commit is one append
    // to the -wal file. synchronous=NORMAL keeps committed data across a process kill (the OS
    // has it); only a power loss may lose the last transactions.
    if (!q.exec(QStringLiteral("PRAGMA journal_mode=WAL")) || !q.next() ||
        q.value(0).toString().toLower() != QStringLiteral("wal"))
      return "cannot switch " + path + " to WAL mode";
    if (!q.exec(QStringLiteral("PRAGMA synchronous=NORMAL")))
      return sqlError(QStringLiteral("PRAGMA synchronous"), q.lastError());
    for (const char* statement : kSchema) {
      if (!q.exec(QString::fromLatin1(statement)))
        return sqlError(QStringLiteral("cannot create tables in ") + qs(path), q.lastError());
    }
    Batch first;
    first.meta.emplace_back("format_version", std::to_string(kFormatVersion));
    first.meta.emplace_back(
        "created_utc", QDateTime::currentDateTimeUtc().toString(Qt::ISODateWithMs).toStdString());
    for (const auto& [key, value] : meta)
      first.meta.emplace_back(key, value);
    return write(db, first);
  }

  void loop(QSqlDatabase& db) {
    const auto period = std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(config.flush_period_s));
    auto next = std::chrono::steady_clock::now() + period;
    for (;;) {
      Batch batch;
      std::uint64_t upto = 0;
      bool last = false;
      {
        std::unique_lock lock(mutex);
        wake.wait_until(lock, next, [this] { return stop || flush_now; });
        flush_now = false;
        batch = std::exchange(pending, Batch{});
        upto = enqueued;
        last = stop;
      }
      next = std::chrono::steady_clock::now() + period;
      std::string error;
      if (batch.rows() > 0)
        error = write(db, batch);
      {
        const std::lock_guard lock(mutex);
        if (batch.rows() > 0) {
          if (error.empty()) {
            ++stats.transactions;
            stats.frames += batch.frames.size();
            for (const auto& f : batch.frames)
              stats.frame_bytes += f.bytes.size();
            stats.events += batch.events.size();
            stats.truth += batch.truth.size();
            stats.commands += batch.commands.size();
          } else {
            stats.dropped_rows += batch.rows();
            stats.last_error = error;
          }
        }
        done = upto;
      }
      committed.notify_all();
      if (last)
        return;
    }
  }

  static std::string write(QSqlDatabase& db, const Batch& batch) {
    if (!db.transaction())
      return sqlError(QStringLiteral("begin transaction"), db.lastError());
    QSqlQuery q(db);
    auto fail = [&](const char* what) {
      const std::string error = sqlError(QString::fromLatin1(what), q.lastError());
      db.rollback();
      return error;
    };
    if (!batch.frames.empty()) {
      q.prepare(QStringLiteral("INSERT INTO frames(t, dir, bytes) VALUES(?, ?, ?)"));
      for (const auto& f : batch.frames) {
        q.bindValue(0, f.t_s);
        q.bindValue(1, static_cast<int>(f.dir));
        q.bindValue(2, QByteArray(reinterpret_cast<const char*>(f.bytes.data()),
                                  static_cast<qsizetype>(f.bytes.size())));
        if (!q.exec())
          return fail("insert frame");
      }
    }
    if (!batch.events.empty()) {
      q.prepare(QStringLiteral("INSERT INTO events(t, kind, text) VALUES(?, ?, ?)"));
      for (const auto& e : batch.events) {
        q.bindValue(0, e.t_s);
        q.bindValue(1, qs(e.kind));
        q.bindValue(2, qs(e.text));
        if (!q.exec())
          return fail("insert event");
      }
    }
    if (!batch.truth.empty()) {
      q.prepare(QStringLiteral("INSERT INTO truth(t, x, y, theta) VALUES(?, ?, ?, ?)"));
      for (const auto& p : batch.truth) {
        q.bindValue(0, p.t_s);
        q.bindValue(1, p.x_m);
        q.bindValue(2, p.y_m);
        q.bindValue(3, p.theta_rad);
        if (!q.exec())
          return fail("insert truth");
      }
    }
    if (!batch.commands.empty()) {
      q.prepare(QStringLiteral("INSERT INTO commands(t, text) VALUES(?, ?)"));
      for (const auto& c : batch.commands) {
        q.bindValue(0, c.t_s);
        q.bindValue(1, qs(c.text));
        if (!q.exec())
          return fail("insert command");
      }
    }
    if (!batch.meta.empty()) {
      q.prepare(QStringLiteral("INSERT OR REPLACE INTO meta(key, value) VALUES(?, ?)"));
      for (const auto& [key, value] : batch.meta) {
        q.bindValue(0, qs(key));
        q.bindValue(1, qs(value));
        if (!q.exec())
          return fail("insert meta");
      }
    }
    if (!db.commit()) {
      const std::string error = sqlError(QStringLiteral("commit"), db.lastError());
      db.rollback();
      return error;
    }
    return {};
  }
};

SessionRecorder::OpenResult SessionRecorder::create(const std::string& path,
                                                    const std::map<std::string, std::string>& meta,
                                                    RecorderConfig config) {
  if (!std::isfinite(config.flush_period_s) || config.flush_period_s <= 0.0 ||
      config.flush_period_s > 1.0 || config.max_queued_rows == 0)
    throw std::invalid_argument(
        "SessionRecorder: flush_period_s must be in (0, 1] s and max_queued_rows > 0");
  if (path.empty())
    return {nullptr, "recording: empty file name"};
  const QFileInfo info(qs(path));
  if (info.exists() && (!info.isFile() || info.size() > 0))
    return {nullptr, "recording: " + path + " already exists (recordings are never overwritten)"};
  if (!info.absoluteDir().exists())
    return {nullptr,
            "recording: directory " + info.absolutePath().toStdString() + " does not exist"};

  auto shared = std::make_shared<Shared>();
  shared->config = config;
  shared->path = path;
  std::promise<std::string> opened;
  std::future<std::string> result = opened.get_future();
  shared->writer = std::thread([raw = shared.get(), p = std::move(opened), meta]() mutable {
    raw->run(std::move(p), std::move(meta));
  });
  const std::string error = result.get();
  if (!error.empty()) {
    shared->writer.join();  // run() returned after reporting the failure
    return {nullptr, "recording: " + error};
  }
  return {std::unique_ptr<SessionRecorder>(new SessionRecorder(path, std::move(shared))), {}};
}

SessionRecorder::SessionRecorder(std::string path, std::shared_ptr<Shared> shared)
    : path_(std::move(path)), shared_(std::move(shared)) {}

SessionRecorder::~SessionRecorder() {
  {
    const std::lock_guard lock(shared_->mutex);
    shared_->stop = true;
    shared_->closed = true;
  }
  shared_->wake.notify_all();
  if (shared_->writer.joinable())
    shared_->writer.join();
}

void SessionRecorder::recordFrame(comms::TapDirection direction,
                                  std::chrono::steady_clock::time_point time,
                                  std::span<const std::uint8_t> bytes) {
  RecordedFrame frame{shared_->seconds(time), static_cast<std::uint8_t>(direction),
                      std::vector<std::uint8_t>(bytes.begin(), bytes.end())};
  shared_->enqueue([&](Batch& b) { b.frames.push_back(std::move(frame)); });
}

void SessionRecorder::recordEvent(std::string_view kind, std::string_view text) {
  RecordedEvent event{now_s(), std::string(kind), std::string(text)};
  shared_->enqueue([&](Batch& b) { b.events.push_back(std::move(event)); });
}

void SessionRecorder::recordTruth(double x_m, double y_m, double theta_rad) {
  if (!std::isfinite(x_m) || !std::isfinite(y_m) || !std::isfinite(theta_rad))
    return;
  const RecordedTruth truth{now_s(), x_m, y_m, theta_rad};
  shared_->enqueue([&](Batch& b) { b.truth.push_back(truth); });
}

void SessionRecorder::recordCommand(std::string_view text) {
  RecordedCommand command{now_s(), std::string(text)};
  shared_->enqueue([&](Batch& b) { b.commands.push_back(std::move(command)); });
}

void SessionRecorder::setMeta(std::string_view key, std::string_view value) {
  shared_->enqueue([&](Batch& b) { b.meta.emplace_back(std::string(key), std::string(value)); });
}

comms::FrameTap SessionRecorder::tap() const {
  // Holds the shared state, not the recorder: a link may outlive the recorder.
  return
      [shared = shared_](comms::TapDirection direction, std::chrono::steady_clock::time_point time,
                         std::span<const std::uint8_t> bytes) {
        RecordedFrame frame{shared->seconds(time), static_cast<std::uint8_t>(direction),
                            std::vector<std::uint8_t>(bytes.begin(), bytes.end())};
        shared->enqueue([&](Batch& b) { b.frames.push_back(std::move(frame)); });
      };
}

double SessionRecorder::now_s() const {
  return shared_->seconds(std::chrono::steady_clock::now());
}

void SessionRecorder::flush() {
  std::unique_lock lock(shared_->mutex);
  const std::uint64_t target = shared_->enqueued;
  shared_->flush_now = true;
  shared_->wake.notify_all();
  shared_->committed.wait(lock, [&] { return shared_->done >= target; });
}

RecorderStats SessionRecorder::stats() const {
  const std::lock_guard lock(shared_->mutex);
  return shared_->stats;
}

}  // namespace irgs::recording
