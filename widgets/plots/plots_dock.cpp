#include "widgets/plots/plots_dock.hpp"

#include <QComboBox>
#include <QFileDialog>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QMessageBox>
#include <QSignalBlocker>
#include <QSplitter>
#include <QTimer>
#include <QToolButton>
#include <QVBoxLayout>
#include <algorithm>
#include <array>

#include "widgets/plots/field_browser.hpp"
#include "widgets/plots/plot_data_hub.hpp"
#include "widgets/plots/plot_panel.hpp"

namespace irgs::widgets {
namespace {

struct WindowChoice {
  const char* label;
  double seconds;
};
constexpr std::array<WindowChoice, 7> kWindows{{{"10 s", 10.0},
                                                {"30 s", 30.0},
                                                {"1 min", 60.0},
                                                {"2 min", 120.0},
                                                {"5 min", 300.0},
                                                {"10 min", 600.0},
                                                {"30 min", 1800.0}}};

QToolButton* toolButton(const QString& text, const QString& tip, QWidget* parent) {
  auto* button = new QToolButton(parent);
  button->setText(text);
  button->setToolTip(tip);
  button->setAutoRaise(true);
  return button;
}

}  // namespace

PlotsDock::PlotsDock(PlotDataHub& hub, QWidget* parent) : QWidget(parent), hub_(hub) {
  auto* browser_side = new QWidget(this);
  auto* browser_layout = new QVBoxLayout(browser_side);
  browser_layout->setContentsMargins(0, 0, 0, 0);
  filter_ = new QLineEdit(browser_side);
  filter_->setPlaceholderText(tr("Filter fields"));
  filter_->setClearButtonEnabled(true);
  browser_ = new FieldBrowser(hub_, browser_side);
  browser_->setColumnWidth(0, 215);  // MAVLink message names under two levels of indent
  browser_layout->addWidget(filter_);
  browser_layout->addWidget(browser_);
  connect(filter_, &QLineEdit::textChanged, browser_, &FieldBrowser::setFilter);
  connect(browser_, &FieldBrowser::fieldsActivated, this, &PlotsDock::plotFields);

  auto* plots_side = new QWidget(this);
  auto* plots_layout = new QVBoxLayout(plots_side);
  plots_layout->setContentsMargins(0, 0, 0, 0);
  auto* bar = new QHBoxLayout;
  QToolButton* add = toolButton(tr("+ Plot"), tr("Add a plot panel"), plots_side);
  QToolButton* remove = toolButton(tr("− Plot"), tr("Remove the current plot panel"), plots_side);
  pause_button_ = toolButton(tr("Pause"), tr("Pause / resume every plot"), plots_side);
  pause_button_->setCheckable(true);
  window_choice_ = new QComboBox(plots_side);
  for (const WindowChoice& w : kWindows)
    window_choice_->addItem(tr(w.label), w.seconds);
  window_choice_->setCurrentIndex(1);
  window_choice_->setToolTip(tr("Time window of every plot (the mouse wheel zooms one plot)"));
  QToolButton* csv =
      toolButton(tr("CSV…"), tr("Export the current plot's window as CSV"), plots_side);
  QToolButton* png = toolButton(tr("PNG…"), tr("Export the current plot as PNG"), plots_side);
  bar->addWidget(add);
  bar->addWidget(remove);
  bar->addWidget(pause_button_);
  bar->addWidget(new QLabel(tr("Window:"), plots_side));
  bar->addWidget(window_choice_);
  bar->addStretch(1);
  bar->addWidget(csv);
  bar->addWidget(png);
  plots_layout->addLayout(bar);
  panel_column_ = new QSplitter(Qt::Vertical, plots_side);
  panel_column_->setChildrenCollapsible(false);
  plots_layout->addWidget(panel_column_, 1);

  auto* split = new QSplitter(Qt::Horizontal, this);
  split->addWidget(browser_side);
  split->addWidget(plots_side);
  split->setStretchFactor(0, 0);
  split->setStretchFactor(1, 1);
  split->setSizes({300, 700});
  auto* layout = new QHBoxLayout(this);
  layout->setContentsMargins(2, 2, 2, 2);
  layout->addWidget(split);

  connect(add, &QToolButton::clicked, this, [this] { addPanel(); });
  connect(remove, &QToolButton::clicked, this, &PlotsDock::removeCurrentPanel);
  connect(pause_button_, &QToolButton::toggled, this, &PlotsDock::setAllPaused);
  connect(window_choice_, &QComboBox::currentIndexChanged, this,
          [this](int) { setWindow_s(window_choice_->currentData().toDouble()); });
  connect(csv, &QToolButton::clicked, this, [this] { exportCurrent(false); });
  connect(png, &QToolButton::clicked, this, [this] { exportCurrent(true); });

  addPanel();
  addPanel();
  setCurrentPanel(panels_.front());

  refresh_ = new QTimer(this);
  refresh_->setInterval(kRefreshInterval_ms);
  connect(refresh_, &QTimer::timeout, this, &PlotsDock::refreshNow);
  refresh_->start();
}

PlotsDock::~PlotsDock() = default;

PlotPanel* PlotsDock::addPanel() {
  if (panelCount() >= kMaxPanels)
    return nullptr;
  auto* panel = new PlotPanel(hub_, panel_column_);
  panel->setWindow_s(window_choice_->currentData().toDouble());
  panel->setPaused(pause_button_->isChecked());
  panel_column_->addWidget(panel);
  panels_.push_back(panel);
  connect(panel, &PlotPanel::activated, this, &PlotsDock::setCurrentPanel);
  setCurrentPanel(panel);
  return panel;
}

void PlotsDock::removeCurrentPanel() {
  if (panels_.size() <= 1 || current_ == nullptr)
    return;
  const auto it = std::find(panels_.begin(), panels_.end(), current_);
  if (it == panels_.end())
    return;
  const auto index = static_cast<std::size_t>(it - panels_.begin());
  panels_.erase(it);
  current_->deleteLater();
  current_->hide();
  current_ = nullptr;
  setCurrentPanel(panels_[std::min(index, panels_.size() - 1)]);
}

void PlotsDock::setCurrentPanel(PlotPanel* panel) {
  current_ = panel;
  for (PlotPanel* p : panels_)
    p->setCurrent(p == panel);
}

void PlotsDock::plotFields(const QStringList& keys) {
  if (current_ == nullptr)
    return;
  for (const QString& key : keys)
    current_->addField(key);
}

void PlotsDock::setAllPaused(bool paused) {
  for (PlotPanel* p : panels_)
    p->setPaused(paused);
  if (pause_button_->isChecked() != paused)
    pause_button_->setChecked(paused);
  pause_button_->setText(paused ? tr("Resume") : tr("Pause"));
}

void PlotsDock::setWindow_s(double window_s) {
  for (PlotPanel* p : panels_)
    p->setWindow_s(window_s);
  const int index = window_choice_->findData(window_s);
  if (index >= 0 && index != window_choice_->currentIndex()) {
    const QSignalBlocker block(window_choice_);
    window_choice_->setCurrentIndex(index);
  }
}

void PlotsDock::refreshNow() {
  for (PlotPanel* p : panels_)
    p->refresh();
}

void PlotsDock::exportCurrent(bool png) {
  if (current_ == nullptr)
    return;
  const QString path =
      png ? QFileDialog::getSaveFileName(this, tr("Export Plot as PNG"), QStringLiteral("plot.png"),
                                         tr("PNG (*.png)"))
          : QFileDialog::getSaveFileName(this, tr("Export Plot as CSV"), QStringLiteral("plot.csv"),
                                         tr("CSV (*.csv)"));
  if (path.isEmpty())
    return;
  const QString error = png ? current_->exportPng(path) : current_->exportCsv(path);
  if (!error.isEmpty())
    QMessageBox::warning(this, png ? tr("Export PNG") : tr("Export CSV"), error);
}

}  // namespace irgs::widgets
