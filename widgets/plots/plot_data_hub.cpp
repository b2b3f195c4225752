#include "widgets/plots/plot_data_hub.hpp"

#include <algorithm>

namespace irgs::widgets {

PlotDataHub::PlotDataHub(std::size_t capacity_per_field, QObject* parent)
    : QObject(parent), capacity_(capacity_per_field) {}

PlotDataHub::~PlotDataHub() = default;

void PlotDataHub::record(const QString& key, const QString& unit, double time_s, double value,
                         std::size_t capacity) {
  auto it = fields_.find(key);
  bool added = false;
  if (it == fields_.end()) {
    it = fields_
             .emplace(key, std::make_unique<Field>(
                               Field{unit, PlotSeries(capacity > 0 ? capacity : capacity_)}))
             .first;
    added = true;
  }
  if (it->second->series.append(time_s, value)) {
    // A restart (time far back) lowers the live edge too.
    latest_s_ =
        time_s < latest_s_ - PlotSeries::kRestartGap_s ? time_s : std::max(latest_s_, time_s);
    ++revision_;
  }
  if (added)
    emit fieldAdded(key);
}

void PlotDataHub::record(double time_s, const std::vector<PlotFieldValue>& values) {
  for (const PlotFieldValue& v : values)
    record(v.key, v.unit, time_s, v.value);
}

void PlotDataHub::clearSamples() {
  for (auto& [key, field] : fields_)
    field->series.clear();
  latest_s_ = 0.0;
  ++revision_;
}

QStringList PlotDataHub::keys() const {
  QStringList out;
  for (const auto& [key, field] : fields_)
    out << key;
  return out;
}

const PlotSeries* PlotDataHub::series(const QString& key) const {
  const auto it = fields_.find(key);
  return it == fields_.end() ? nullptr : &it->second->series;
}

QString PlotDataHub::unit(const QString& key) const {
  const auto it = fields_.find(key);
  return it == fields_.end() ? QString() : it->second->unit;
}

}  // namespace irgs::widgets
