#pragma once
// A side-column page that scrolls vertically instead of setting the window's minimum height.
//
// Why: a QTabWidget is as tall as its tallest page's minimum, and the side column's pages (the
// Drive tab once linked, with behaviours and the pad; the Edit tab with a selection) are taller
// than a laptop screen leaves for them. In a ScrollColumn the page's minimum is small; its size
// hint stays the content's, so the main window still gives the page the room it asks for when
// there is room (MainWindow::fitSideColumnToTab), and a change of the content's size (a group
// shown or hidden) is announced to the layouts above as a geometry change.

#include <QScrollArea>

class QVBoxLayout;

namespace irgs::widgets {

class ScrollColumn : public QScrollArea {
  Q_OBJECT

 public:
  explicit ScrollColumn(QWidget* parent = nullptr);

  // The content's column: add the page's groups here.
  QVBoxLayout& column() const { return *column_; }
  QWidget& content() const { return *content_; }

  // The content's size hint, plus the vertical scroll bar's width.
  QSize sizeHint() const override;
  bool eventFilter(QObject* watched, QEvent* event) override;

 private:
  QWidget* content_ = nullptr;
  QVBoxLayout* column_ = nullptr;
};

}  // namespace irgs::widgets
