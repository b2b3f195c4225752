#pragma once
// Every numeric field the plots can show, by key, with its samples. A key is a path of the
// source tree the field browser shows, e.g. "Telemetry/Odometry pose/x"; each field has a unit
// and a PlotSeries. Producers (the app's plot feed) record values; the browser lists the keys
// and the panels draw the series. Recording does not repaint anything: panels redraw on their
// own timer, so the feed rate never sets the frame rate.

#include <QObject>
#include <QString>
#include <QStringList>
#include <map>
#include <memory>
#include <vector>

#include "widgets/plots/plot_series.hpp"

namespace irgs::widgets {

struct PlotFieldValue {
  QString key;  // "Source/Group/name"
  QString unit;
  double value = 0.0;
};

class PlotDataHub : public QObject {
  Q_OBJECT

 public:
  explicit PlotDataHub(std::size_t capacity_per_field = PlotSeries::kDefaultCapacity,
                       QObject* parent = nullptr);
  ~PlotDataHub() override;

  // Records one value (a new key is added and announced with fieldAdded()). `capacity` is the
  // new key's sample count (0: the hub's); an existing key keeps its own.
  void record(const QString& key, const QString& unit, double time_s, double value,
              std::size_t capacity = 0);
  void record(double time_s, const std::vector<PlotFieldValue>& values);
  // Drops every sample (keys stay, so panels keep their traces).
  void clearSamples();

  QStringList keys() const;  // sorted
  bool contains(const QString& key) const { return fields_.count(key) > 0; }
  const PlotSeries* series(const QString& key) const;
  QString unit(const QString& key) const;
  // Newest sample time over all fields (the live edge of the plots); 0 when empty.
  double latestTime_s() const { return latest_s_; }
  // Bumped on every record(): panels repaint only when it changed.
  std::uint64_t revision() const { return revision_; }

 signals:
  void fieldAdded(const QString& key);

 private:
  struct Field {
    QString unit;
    PlotSeries series;
  };
  std::size_t capacity_;
  std::map<QString, std::unique_ptr<Field>> fields_;
  double latest_s_ = 0.0;
  std::uint64_t revision_ = 0;
};

}  // namespace irgs::widgets
