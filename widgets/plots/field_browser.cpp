#include "widgets/plots/field_browser.hpp"

#include <QKeyEvent>
#include <QMimeData>
#include <functional>

#include "widgets/plots/plot_data_hub.hpp"
#include "widgets/plots/plot_panel.hpp"

namespace irgs::widgets {
namespace {

QStringList keysOf(const QList<QTreeWidgetItem*>& items) {
  QStringList keys;
  for (const QTreeWidgetItem* item : items) {
    const QString key = item->data(0, FieldBrowser::kKeyRole).toString();
    if (!key.isEmpty())
      keys << key;
  }
  return keys;
}

// Text order with digit runs compared as numbers, so "range[2]" comes before "range[10]" and
// "id 9" before "id 10" (zero-padded names such as "range 03" keep their order).
int naturalCompare(const QString& a, const QString& b) {
  qsizetype i = 0;
  qsizetype j = 0;
  while (i < a.size() && j < b.size()) {
    if (a[i].isDigit() && b[j].isDigit()) {
      const qsizetype i0 = i;
      const qsizetype j0 = j;
      while (i < a.size() && a[i].isDigit())
        ++i;
      while (j < b.size() && b[j].isDigit())
        ++j;
      const qulonglong na = QStringView(a).mid(i0, i - i0).toULongLong();
      const qulonglong nb = QStringView(b).mid(j0, j - j0).toULongLong();
      if (na != nb)
        return na < nb ? -1 : 1;
      continue;
    }
    if (a[i] != b[j])
      return a[i] < b[j] ? -1 : 1;
    ++i;
    ++j;
  }
  return a.size() - i == b.size() - j ? QString::compare(a, b)
                                      : (a.size() - i < b.size() - j ? -1 : 1);
}

}  // namespace

FieldBrowser::FieldBrowser(PlotDataHub& hub, QWidget* parent) : QTreeWidget(parent), hub_(hub) {
  setHeaderLabels({tr("Field"), tr("Unit")});
  setColumnCount(2);
  setSelectionMode(QAbstractItemView::ExtendedSelection);
  setDragEnabled(true);
  setDragDropMode(QAbstractItemView::DragOnly);
  setUniformRowHeights(true);
  setToolTip(tr("Drag fields onto a plot, or double-click to add to the current plot"));
  for (const QString& key : hub_.keys())
    addKey(key);
  connect(&hub_, &PlotDataHub::fieldAdded, this, &FieldBrowser::addKey);
  connect(this, &QTreeWidget::itemDoubleClicked, this, [this](QTreeWidgetItem* item, int) {
    const QStringList keys = keysOf({item});
    if (!keys.isEmpty())
      emit fieldsActivated(keys);
  });
}

void FieldBrowser::addKey(const QString& key) {
  const QStringList parts = key.split(QLatin1Char('/'), Qt::SkipEmptyParts);
  if (parts.isEmpty())
    return;
  QTreeWidgetItem* parent = nullptr;
  for (qsizetype i = 0; i < parts.size(); ++i) {
    const bool leaf = i == parts.size() - 1;
    QTreeWidgetItem* found = nullptr;
    const int count = parent != nullptr ? parent->childCount() : topLevelItemCount();
    int insert_at = count;
    for (int c = 0; c < count; ++c) {
      QTreeWidgetItem* child = parent != nullptr ? parent->child(c) : topLevelItem(c);
      if (child->text(0) == parts[i] && child->data(0, kKeyRole).toString().isEmpty() != leaf) {
        found = child;
        break;
      }
      // Kept sorted, so sonar 00..15 and the groups read in order.
      if (insert_at == count && naturalCompare(child->text(0), parts[i]) > 0)
        insert_at = c;
    }
    if (found == nullptr) {
      found = new QTreeWidgetItem(QStringList{parts[i]});
      if (parent != nullptr)
        parent->insertChild(insert_at, found);
      else
        insertTopLevelItem(insert_at, found);
      // The whole path on hover: deep names (MAVLink messages) may not fit the column.
      found->setToolTip(0, parts.mid(0, i + 1).join(QLatin1Char('/')));
      if (leaf) {
        found->setData(0, kKeyRole, key);
        found->setText(1, hub_.unit(key));
        found->setFlags(Qt::ItemIsEnabled | Qt::ItemIsSelectable | Qt::ItemIsDragEnabled);
      } else {
        found->setFlags(Qt::ItemIsEnabled);
        found->setExpanded(parent == nullptr);
      }
    }
    parent = found;
  }
  if (!filter_.isEmpty())
    setFilter(filter_);
}

QTreeWidgetItem* FieldBrowser::itemFor(const QString& key) const {
  for (QTreeWidgetItemIterator it(const_cast<FieldBrowser*>(this)); *it != nullptr; ++it) {
    if ((*it)->data(0, kKeyRole).toString() == key)
      return *it;
  }
  return nullptr;
}

QStringList FieldBrowser::selectedKeys() const {
  QStringList keys;
  for (QTreeWidgetItemIterator it(const_cast<FieldBrowser*>(this),
                                  QTreeWidgetItemIterator::Selected);
       *it != nullptr; ++it) {
    const QString key = (*it)->data(0, kKeyRole).toString();
    if (!key.isEmpty())
      keys << key;
  }
  return keys;
}

void FieldBrowser::setFilter(const QString& text) {
  filter_ = text;
  // Leaves first, then groups visible when any child is.
  std::function<bool(QTreeWidgetItem*)> apply = [&](QTreeWidgetItem* item) {
    const QString key = item->data(0, kKeyRole).toString();
    if (!key.isEmpty()) {
      const bool show = text.isEmpty() || key.contains(text, Qt::CaseInsensitive);
      item->setHidden(!show);
      return show;
    }
    bool any = false;
    for (int c = 0; c < item->childCount(); ++c)
      any = apply(item->child(c)) || any;
    item->setHidden(!any);
    if (any && !text.isEmpty())
      item->setExpanded(true);
    return any;
  };
  for (int i = 0; i < topLevelItemCount(); ++i)
    apply(topLevelItem(i));
}

QStringList FieldBrowser::mimeTypes() const {
  return {QString::fromLatin1(kFieldMimeType)};
}

QMimeData* FieldBrowser::mimeData(const QList<QTreeWidgetItem*>& items) const {
  const QStringList keys = keysOf(items);
  if (keys.isEmpty())
    return nullptr;
  auto* mime = new QMimeData;
  mime->setData(QString::fromLatin1(kFieldMimeType), keys.join(QLatin1Char('\n')).toUtf8());
  mime->setText(keys.join(QLatin1Char('\n')));
  return mime;
}

void FieldBrowser::keyPressEvent(QKeyEvent* event) {
  if (event->key() == Qt::Key_Return || event->key() == Qt::Key_Enter) {
    const QStringList keys = selectedKeys();
    if (!keys.isEmpty()) {
      emit fieldsActivated(keys);
      return;
    }
  }
  QTreeWidget::keyPressEvent(event);
}

}  // namespace irgs::widgets
