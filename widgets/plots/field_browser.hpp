#pragma once
// The plots dock's field browser: every field of a PlotDataHub as a tree by source
// ("Telemetry" > "Odometry pose" > "x [m]"), growing as new fields arrive. Leaves drag onto a
// plot panel (MIME kFieldMimeType, several at once with a multi-selection); a double-click or
// Enter on a leaf asks for it to be plotted in the current panel (fieldsActivated).

#include <QStringList>
#include <QTreeWidget>

namespace irgs::widgets {

class PlotDataHub;

class FieldBrowser : public QTreeWidget {
  Q_OBJECT

 public:
  static constexpr int kKeyRole = Qt::UserRole + 1;

  explicit FieldBrowser(PlotDataHub& hub, QWidget* parent = nullptr);

  // The leaf item of `key`, or null.
  QTreeWidgetItem* itemFor(const QString& key) const;
  // The keys of the selected leaves, in tree order.
  QStringList selectedKeys() const;
  // Shows only fields whose key contains `text` (case-insensitive); empty shows all.
  void setFilter(const QString& text);

 signals:
  void fieldsActivated(const QStringList& keys);

 public:
  // What a drag of `items` carries (public so tests can drop exactly that on a panel).
  QStringList mimeTypes() const override;
  QMimeData* mimeData(const QList<QTreeWidgetItem*>& items) const override;

 protected:
  void keyPressEvent(QKeyEvent* event) override;

 private:
  void addKey(const QString& key);

  PlotDataHub& hub_;
  QString filter_;
};

}  // namespace irgs::widgets
