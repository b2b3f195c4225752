#include "widgets/layout/scroll_column.hpp"

#include <QEvent>
#include <QScrollBar>
#include <QStyle>
#include <QVBoxLayout>

namespace irgs::widgets {

ScrollColumn::ScrollColumn(QWidget* parent) : QScrollArea(parent) {
  setFrameShape(QFrame::NoFrame);
  setWidgetResizable(true);
  // No horizontal scrolling: the column is as wide as the content needs, beside the scroll bar.
  setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
  content_ = new QWidget(this);
  column_ = new QVBoxLayout(content_);
  setWidget(content_);
  content_->installEventFilter(this);
}

bool ScrollColumn::eventFilter(QObject* watched, QEvent* event) {
  if (watched == content_ && event->type() == QEvent::LayoutRequest) {
    setMinimumWidth(content_->minimumSizeHint().width() +
                    style()->pixelMetric(QStyle::PM_ScrollBarExtent));
    updateGeometry();  // the content's size hint is ours
  }
  return QScrollArea::eventFilter(watched, event);
}

QSize ScrollColumn::sizeHint() const {
  return content_->sizeHint() + QSize(style()->pixelMetric(QStyle::PM_ScrollBarExtent), 0);
}

}  // namespace irgs::widgets
