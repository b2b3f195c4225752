#include "widgets/params/parameter_table.hpp"

#include <QDoubleSpinBox>
#include <QHeaderView>
#include <QRegularExpression>
#include <algorithm>
#include <cmath>

namespace irgs::widgets {
namespace {

enum Column { kName = 0, kValue, kUnit, kRange, kDefault, kStatus, kColumns };

QString number(double v, int decimals) {
  QString text = QString::number(v, 'f', decimals);
  if (decimals > 0)
    text.remove(QRegularExpression(QStringLiteral("\\.?0+$")));
  return text;
}

}  // namespace

ParameterTable::ParameterTable(QWidget* parent) : QTreeWidget(parent) {
  setColumnCount(kColumns);
  setHeaderLabels({tr("Parameter"), tr("Value"), tr("Unit"), tr("Range"), tr("Default"), tr("")});
  setRootIsDecorated(true);
  setUniformRowHeights(true);
  setSelectionMode(QAbstractItemView::NoSelection);
  header()->setSectionResizeMode(kName, QHeaderView::ResizeToContents);
  header()->setSectionResizeMode(kValue, QHeaderView::Fixed);
  header()->resizeSection(kValue, 96);
  header()->setSectionResizeMode(kUnit, QHeaderView::ResizeToContents);
  header()->setSectionResizeMode(kRange, QHeaderView::ResizeToContents);
  header()->setSectionResizeMode(kDefault, QHeaderView::ResizeToContents);
  header()->setStretchLastSection(true);
}

QTreeWidgetItem* ParameterTable::sectionItem(const QString& title, bool create) {
  for (int i = 0; i < topLevelItemCount(); ++i) {
    if (topLevelItem(i)->text(kName) == title)
      return topLevelItem(i);
  }
  if (!create)
    return nullptr;
  auto* item = new QTreeWidgetItem(this, QStringList{title});
  QFont bold = item->font(kName);
  bold.setBold(true);
  item->setFont(kName, bold);
  item->setFirstColumnSpanned(true);
  item->setExpanded(true);
  return item;
}

void ParameterTable::clearSection(const QString& title) {
  QTreeWidgetItem* section = sectionItem(title, false);
  if (section == nullptr)
    return;
  std::erase_if(rows_, [&](const Row& r) { return r.section == title; });
  qDeleteAll(section->takeChildren());
}

void ParameterTable::setSection(const QString& title, const std::vector<ParameterSpec>& specs) {
  clearSection(title);
  QTreeWidgetItem* section = sectionItem(title, true);
  section->setExpanded(true);
  for (const ParameterSpec& spec : specs) {
    auto* item = new QTreeWidgetItem(section);
    item->setText(kName, spec.label);
    item->setText(kUnit, spec.unit);
    if (spec.max > spec.min)
      item->setText(kRange, QStringLiteral("%1 … %2").arg(number(spec.min, spec.decimals),
                                                          number(spec.max, spec.decimals)));
    if (spec.default_value)
      item->setText(kDefault, number(*spec.default_value, spec.decimals));
    const QString tip = spec.description.isEmpty() ? spec.key : spec.description;
    for (int c = 0; c < kColumns; ++c)
      item->setToolTip(c, tip);
    Row row{spec, item, nullptr, title};
    if (spec.read_only) {
      item->setText(kValue, number(spec.value, spec.decimals));
    } else {
      auto* box = new QDoubleSpinBox(this);
      box->setDecimals(spec.decimals);
      box->setRange(spec.min, spec.max);
      box->setSingleStep(std::pow(10.0, -std::max(0, spec.decimals - 1)));
      box->setValue(spec.value);
      box->setKeyboardTracking(false);
      box->setToolTip(tip);
      box->setFrame(false);
      setItemWidget(item, kValue, box);
      row.editor = box;
      const QString key = spec.key;
      connect(box, &QDoubleSpinBox::editingFinished, this, [this, key] {
        Row* r = find(key);
        if (r == nullptr || r->editor == nullptr)
          return;
        const double v = r->editor->value();
        if (v == r->spec.value)
          return;
        r->spec.value = v;
        emit valueEdited(key, v);
      });
    }
    rows_.push_back(std::move(row));
  }
}

ParameterTable::Row* ParameterTable::find(const QString& key) {
  const auto it =
      std::find_if(rows_.begin(), rows_.end(), [&](const Row& r) { return r.spec.key == key; });
  return it == rows_.end() ? nullptr : &*it;
}

const ParameterTable::Row* ParameterTable::find(const QString& key) const {
  return const_cast<ParameterTable*>(this)->find(key);
}

bool ParameterTable::setValue(const QString& key, double value) {
  Row* r = find(key);
  if (r == nullptr)
    return false;
  r->spec.value = value;
  if (r->editor != nullptr) {
    const QSignalBlocker block(r->editor);
    r->editor->setValue(value);
  } else {
    r->item->setText(kValue, number(value, r->spec.decimals));
  }
  return true;
}

std::optional<double> ParameterTable::value(const QString& key) const {
  const Row* r = find(key);
  if (r == nullptr)
    return std::nullopt;
  return r->spec.value;
}

std::optional<ParameterSpec> ParameterTable::spec(const QString& key) const {
  const Row* r = find(key);
  if (r == nullptr)
    return std::nullopt;
  return r->spec;
}

void ParameterTable::setStatus(const QString& key, const QString& status) {
  if (Row* r = find(key))
    r->item->setText(kStatus, status);
}

QString ParameterTable::status(const QString& key) const {
  const Row* r = find(key);
  return r == nullptr ? QString() : r->item->text(kStatus);
}

QDoubleSpinBox* ParameterTable::editor(const QString& key) const {
  const Row* r = find(key);
  return r == nullptr ? nullptr : r->editor;
}

void ParameterTable::restoreDefaults(const QString& section) {
  std::vector<std::pair<QString, double>> changed;
  for (Row& r : rows_) {
    if (r.section != section || r.editor == nullptr || !r.spec.default_value ||
        *r.spec.default_value == r.spec.value)
      continue;
    changed.emplace_back(r.spec.key, *r.spec.default_value);
  }
  for (const auto& [key, v] : changed) {
    setValue(key, v);
    emit valueEdited(key, v);
  }
}

}  // namespace irgs::widgets
