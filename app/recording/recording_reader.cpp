#include "app/recording/recording_reader.hpp"

#include <QFileInfo>
#include <QSqlDatabase>
#include <QSqlError>
#include <QSqlQuery>
#include <QString>
#include <QStringList>
#include <QVariant>

#include <algorithm>
#include <atomic>
#include <cmath>

namespace irgs::recording {

namespace {

std::atomic<std::uint64_t> g_reader_counter{0};

bool finiteTime(const QVariant& v, double& t) {
  bool ok = false;
  t = v.toDouble(&ok);
  return ok && std::isfinite(t) && t >= 0.0;
}

std::string readAll(QSqlDatabase& db, const std::string& path, Recording& rec,
                    std::vector<std::string>& warnings) {
  const QStringList tables = db.tables();
  for (const char* table : {"meta", "frames", "events", "truth", "commands"}) {
    if (!tables.contains(QString::fromLatin1(table)))
      return path + " is not an IRGS recording (no table '" + table + "')";
  }
  QSqlQuery q(db);
  q.setForwardOnly(true);
  if (!q.exec(QStringLiteral("SELECT key, value FROM meta")))
    return "cannot read " + path + ": " + q.lastError().text().toStdString();
  while (q.next())
    rec.meta[q.value(0).toString().toStdString()] = q.value(1).toString().toStdString();
  const auto version = rec.meta.find("format_version");
  if (version == rec.meta.end())
    return path + " is not an IRGS recording (no format_version)";
  bool ok = false;
  const int v = QString::fromStdString(version->second).toInt(&ok);
  if (!ok || v < 1 || v > kFormatVersion)
    return path + " has recording format " + version->second + "; this IRGS reads 1.." +
           std::to_string(kFormatVersion);

  std::size_t skipped = 0;
  double t = 0.0;
  if (!q.exec(QStringLiteral("SELECT t, dir, bytes FROM frames ORDER BY t, id")))
    return "cannot read frames of " + path + ": " + q.lastError().text().toStdString();
  while (q.next()) {
    const int dir = q.value(1).toInt(&ok);
    const QByteArray bytes = q.value(2).toByteArray();
    if (!finiteTime(q.value(0), t) || !ok || (dir != 0 && dir != 1) || bytes.isEmpty()) {
      ++skipped;
      continue;
    }
    RecordedFrame& f = rec.frames.emplace_back();
    f.t_s = t;
    f.dir = static_cast<std::uint8_t>(dir);
    f.bytes.assign(reinterpret_cast<const std::uint8_t*>(bytes.constData()),
                   reinterpret_cast<const std::uint8_t*>(bytes.constData()) + bytes.size());
  }
  if (!q.exec(QStringLiteral("SELECT t, kind, text FROM events ORDER BY t, id")))
    return "cannot read events of " + path + ": " + q.lastError().text().toStdString();
  while (q.next()) {
    if (!finiteTime(q.value(0), t)) {
      ++skipped;
      continue;
    }
    rec.events.push_back(
        {t, q.value(1).toString().toStdString(), q.value(2).toString().toStdString()});
  }
  if (!q.exec(QStringLiteral("SELECT t, x, y, theta FROM truth ORDER BY t, id")))
    return "cannot read truth of " + path + ": " + q.lastError().text().toStdString();
  while (q.next()) {
    const double x = q.value(1).toDouble();
    const double y = q.value(2).toDouble();
    const double theta = q.value(3).toDouble();
    if (!finiteTime(q.value(0), t) || !std::isfinite(x) || !std::isfinite(y) ||
        !std::isfinite(theta)) {
      ++skipped;
      continue;
    }
    rec.truth.push_back({t, x, y, theta});
  }
  if (!q.exec(QStringLiteral("SELECT t, text FROM commands ORDER BY t, id")))
    return "cannot read commands of " + path + ": " + q.lastError().text().toStdString();
  while (q.next()) {
    if (!finiteTime(q.value(0), t)) {
      ++skipped;
      continue;
    }
    rec.commands.push_back({t, q.value(1).toString().toStdString()});
  }
  if (skipped > 0)
    warnings.push_back(path + ": skipped " + std::to_string(skipped) +
                       " unusable rows (bad time, direction or empty frame)");
  return {};
}

}  // namespace

LoadResult loadRecording(const std::string& path) {
  LoadResult result;
  const QFileInfo info(QString::fromStdString(path));
  if (!info.isFile()) {
    result.error = "recording " + path + " does not exist";
    return result;
  }
  const QString name = QStringLiteral("irgs_reader_%1").arg(g_reader_counter.fetch_add(1));
  {
    QSqlDatabase db = QSqlDatabase::addDatabase(QStringLiteral("QSQLITE"), name);
    if (!db.isValid()) {
      result.error = "the Qt SQLite driver (libqt6sql6-sqlite) is not installed";
    } else {
      db.setDatabaseName(info.absoluteFilePath());
      // Read-write when allowed: SQLite then recovers a killed writer's WAL into a consistent
      // state. A read-only file (an archive) still opens read-only.
      if (!info.isWritable())
        db.setConnectOptions(QStringLiteral("QSQLITE_OPEN_READONLY"));
      if (!db.open()) {
        result.error = "cannot open recording " + path + ": " + db.lastError().text().toStdString();
      } else {
        Recording rec;
        result.error = readAll(db, path, rec, result.warnings);
        if (result.error.empty())
          result.recording = std::move(rec);
        db.close();
      }
    }
  }
  QSqlDatabase::removeDatabase(name);
  return result;
}

}  // namespace irgs::recording
