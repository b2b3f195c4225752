#include "widgets/navigation/navigation_panel.hpp"

#include <QComboBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>
#include <QSignalBlocker>
#include <QVBoxLayout>

namespace irgs::widgets {

NavigationPanel::NavigationPanel(QWidget* parent) : QWidget(parent) {
  setObjectName(QStringLiteral("navigationPanel"));
  start_ = new QComboBox(this);
  start_->setObjectName(QStringLiteral("navStart"));
  goal_ = new QComboBox(this);
  goal_->setObjectName(QStringLiteral("navGoal"));
  go_ = new QPushButton(tr("Go"), this);
  go_->setObjectName(QStringLiteral("navGo"));
  abort_ = new QPushButton(tr("Abort"), this);
  abort_->setObjectName(QStringLiteral("navAbort"));
  route_ = new QLabel(tr("No route"), this);
  route_->setWordWrap(true);
  state_ = new QLabel(tr("Idle"), this);
  state_->setObjectName(QStringLiteral("navState"));

  auto* form = new QFormLayout;
  form->addRow(tr("Start node"), start_);
  form->addRow(tr("Goal node"), goal_);
  auto* buttons = new QHBoxLayout;
  buttons->addWidget(go_);
  buttons->addWidget(abort_);
  auto* layout = new QVBoxLayout(this);
  layout->addLayout(form);
  layout->addLayout(buttons);
  layout->addWidget(new QLabel(tr("Route (ceiling markers, A*):"), this));
  layout->addWidget(route_);
  layout->addWidget(new QLabel(tr("State:"), this));
  layout->addWidget(state_);
  layout->addStretch(1);

  connect(go_, &QPushButton::clicked, this,
          [this] { emit goRequested(start_->currentText(), goal_->currentText()); });
  connect(abort_, &QPushButton::clicked, this, &NavigationPanel::abortRequested);
  setRunning(false);
}

void NavigationPanel::setNodes(const QStringList& ids) {
  const QString start = start_->currentText(), goal = goal_->currentText();
  const QSignalBlocker b1(start_), b2(goal_);
  start_->clear();
  goal_->clear();
  start_->addItems(ids);
  goal_->addItems(ids);
  if (ids.contains(start))
    start_->setCurrentText(start);
  if (ids.contains(goal))
    goal_->setCurrentText(goal);
  else if (!ids.isEmpty())
    goal_->setCurrentIndex(static_cast<int>(ids.size()) - 1);
  go_->setEnabled(!ids.isEmpty() && !abort_->isEnabled());
}

QString NavigationPanel::startNode() const {
  return start_->currentText();
}
QString NavigationPanel::goalNode() const {
  return goal_->currentText();
}
void NavigationPanel::setStartNode(const QString& id) {
  const QSignalBlocker block(start_);
  start_->setCurrentText(id);
}
void NavigationPanel::setGoalNode(const QString& id) {
  const QSignalBlocker block(goal_);
  goal_->setCurrentText(id);
}

void NavigationPanel::setRunning(bool running) {
  go_->setEnabled(!running && start_->count() > 0);
  abort_->setEnabled(running);
  start_->setEnabled(!running);
  goal_->setEnabled(!running);
}

void NavigationPanel::setRoute(const QString& text) {
  route_->setText(text);
}
void NavigationPanel::setState(const QString& text) {
  state_->setText(text);
}

}  // namespace irgs::widgets
