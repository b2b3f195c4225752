#pragma once
// The "Navigate" tab: landmark navigation of paper 002 between two nodes of the map's
// topological graph. Start and goal node pickers, Go and Abort, the planned route with the
// action at each marker, and the navigator's state. Setters never emit signals; signals come
// from the user only (like CommandPanel).

#include <QString>
#include <QStringList>
#include <QWidget>

class QComboBox;
class QLabel;
class QPushButton;

namespace irgs::widgets {

class NavigationPanel : public QWidget {
  Q_OBJECT

 public:
  explicit NavigationPanel(QWidget* parent = nullptr);

  // The graph's node ids (keeps the current choices when they still exist).
  void setNodes(const QStringList& ids);
  QString startNode() const;
  QString goalNode() const;
  void setStartNode(const QString& id);
  void setGoalNode(const QString& id);
  // Running: Go disabled, Abort enabled.
  void setRunning(bool running);
  void setRoute(const QString& text);  // "0 → 1 (left) → ..."
  void setState(const QString& text);

  QPushButton& goButton() const { return *go_; }
  QPushButton& abortButton() const { return *abort_; }
  const QLabel& stateLabel() const { return *state_; }

 signals:
  void goRequested(const QString& start, const QString& goal);
  void abortRequested();

 private:
  QComboBox* start_ = nullptr;
  QComboBox* goal_ = nullptr;
  QPushButton* go_ = nullptr;
  QPushButton* abort_ = nullptr;
  QLabel* route_ = nullptr;
  QLabel* state_ = nullptr;
};

}  // namespace irgs::widgets
