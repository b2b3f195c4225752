#pragma once
// The parameters panel's table: named numeric parameters in sections, each with its value (a
// spin box clamped to the range, or read-only text), unit, range, default and a description
// tooltip. Knows nothing of where a parameter comes from: the owner fills sections and reacts to
// valueEdited() (the app applies algorithm parameters and writes firmware ones).

#include <QString>
#include <QTreeWidget>
#include <optional>
#include <vector>

class QDoubleSpinBox;

namespace irgs::widgets {

struct ParameterSpec {
  QString key;    // unique over the table, e.g. "mapping/grid_resolution"
  QString label;  // shown, e.g. "Grid resolution"
  QString unit;
  double min = 0.0;
  double max = 0.0;
  std::optional<double> default_value;
  double value = 0.0;
  int decimals = 3;
  bool read_only = false;
  QString description;
};

class ParameterTable : public QTreeWidget {
  Q_OBJECT

 public:
  explicit ParameterTable(QWidget* parent = nullptr);

  // Replaces the parameters of section `title` (created at the end when new).
  void setSection(const QString& title, const std::vector<ParameterSpec>& specs);
  void clearSection(const QString& title);
  // Shows `value` for `key` without emitting valueEdited(); false for an unknown key.
  bool setValue(const QString& key, double value);
  std::optional<double> value(const QString& key) const;
  std::optional<ParameterSpec> spec(const QString& key) const;
  // Marks a row (e.g. "written", "rejected") in its status column.
  void setStatus(const QString& key, const QString& status);
  QString status(const QString& key) const;
  // The editor of `key` (tests); null for read-only or unknown keys.
  QDoubleSpinBox* editor(const QString& key) const;
  // Resets every editable parameter of the table to its default (emits valueEdited per change).
  void restoreDefaults(const QString& section);

 signals:
  // The user finished editing `key` (Enter or focus out) with a value different from before.
  void valueEdited(const QString& key, double value);

 private:
  struct Row {
    ParameterSpec spec;
    QTreeWidgetItem* item = nullptr;
    QDoubleSpinBox* editor = nullptr;
    QString section;
  };
  QTreeWidgetItem* sectionItem(const QString& title, bool create);
  Row* find(const QString& key);
  const Row* find(const QString& key) const;

  std::vector<Row> rows_;
};

}  // namespace irgs::widgets
