#include "app/gui/rerun_dialog.hpp"

#include <QComboBox>
#include <QDialogButtonBox>
#include <QFormLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QVBoxLayout>

namespace irgs::gui {

RerunDialog::RerunDialog(const QString& recording_name, const recording::RerunParameters& recorded,
                         QWidget* parent)
    : QDialog(parent), recorded_(recorded) {
  setWindowTitle(tr("Re-run %1 with Parameters").arg(recording_name));
  setObjectName(QStringLiteral("rerunDialog"));
  auto* layout = new QVBoxLayout(this);
  auto* intro = new QLabel(
      tr("The recorded sensor stream is decoded as it was live and mapped twice: with the "
         "recorded parameters (the recorded run) and with these. Values the recording does not "
         "hold are the defaults."),
      this);
  intro->setWordWrap(true);
  layout->addWidget(intro);
  auto* columns = new QHBoxLayout;
  layout->addLayout(columns);
  std::map<recording::RerunParameterGroup, QFormLayout*> forms;
  for (auto [group, title] :
       {std::pair{recording::RerunParameterGroup::kMapping, tr("Mapping")},
        std::pair{recording::RerunParameterGroup::kLocalization, tr("Localization")}}) {
    auto* box = new QGroupBox(title, this);
    forms[group] = new QFormLayout(box);
    columns->addWidget(box);
  }
  for (const recording::RerunParameterInfo& info : recording::rerunParameters()) {
    const QString recorded_text =
        QString::fromStdString(recording::rerunParameterValue(recorded_, info.name));
    auto* row = new QWidget(this);
    auto* row_layout = new QHBoxLayout(row);
    row_layout->setContentsMargins(0, 0, 0, 0);
    Editor editor;
    if (!info.choices.empty()) {
      editor.combo = new QComboBox(row);
      editor.combo->setObjectName(QString::fromStdString(info.name));
      for (const std::string& choice : info.choices)
        editor.combo->addItem(QString::fromStdString(choice));
      editor.combo->setCurrentText(recorded_text);
      row_layout->addWidget(editor.combo, 1);
      connect(editor.combo, &QComboBox::currentTextChanged, this,
              [this, name = info.name] { markChanged(name); });
    } else {
      editor.line = new QLineEdit(recorded_text, row);
      editor.line->setObjectName(QString::fromStdString(info.name));
      row_layout->addWidget(editor.line, 1);
      connect(editor.line, &QLineEdit::textChanged, this,
              [this, name = info.name] { markChanged(name); });
    }
    auto* unit = new QLabel(QString::fromStdString(info.unit), row);
    unit->setMinimumWidth(50);
    row_layout->addWidget(unit);
    auto* label = new QLabel(QString::fromStdString(info.label), this);
    const QString tip =
        QString::fromStdString(info.description) + tr(" (recorded: %1)").arg(recorded_text);
    label->setToolTip(tip);
    row->setToolTip(tip);
    forms[info.group]->addRow(label, row);
    editors_[info.name] = editor;
  }
  error_ = new QLabel(this);
  error_->setObjectName(QStringLiteral("rerunError"));
  error_->setStyleSheet(QStringLiteral("color: #c00000"));
  error_->setWordWrap(true);
  layout->addWidget(error_);
  auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel, this);
  buttons->button(QDialogButtonBox::Ok)->setText(tr("Re-run"));
  QPushButton* reset = buttons->addButton(tr("Recorded Values"), QDialogButtonBox::ResetRole);
  connect(reset, &QPushButton::clicked, this, &RerunDialog::resetToRecorded);
  connect(buttons, &QDialogButtonBox::accepted, this, &RerunDialog::accept);
  connect(buttons, &QDialogButtonBox::rejected, this, &RerunDialog::reject);
  layout->addWidget(buttons);
}

QString RerunDialog::value(const std::string& name) const {
  const auto it = editors_.find(name);
  if (it == editors_.end())
    return {};
  return it->second.combo != nullptr ? it->second.combo->currentText() : it->second.line->text();
}

void RerunDialog::setValue(const std::string& name, const QString& text) {
  const auto it = editors_.find(name);
  if (it == editors_.end())
    return;
  if (it->second.combo != nullptr)
    it->second.combo->setCurrentText(text);
  else
    it->second.line->setText(text);
}

void RerunDialog::resetToRecorded() {
  for (const auto& [name, editor] : editors_)
    setValue(name, QString::fromStdString(recording::rerunParameterValue(recorded_, name)));
  error_->clear();
}

void RerunDialog::markChanged(const std::string& name) {
  const auto it = editors_.find(name);
  QWidget* w = it->second.combo != nullptr ? static_cast<QWidget*>(it->second.combo)
                                           : static_cast<QWidget*>(it->second.line);
  QFont font = w->font();
  font.setBold(value(name).toStdString() != recording::rerunParameterValue(recorded_, name));
  w->setFont(font);
}

std::optional<recording::RerunParameters> RerunDialog::parameters() const {
  recording::RerunParameters p = recorded_;
  for (const auto& [name, editor] : editors_) {
    const std::string text = value(name).trimmed().toStdString();
    if (text == recording::rerunParameterValue(recorded_, name))
      continue;  // unchanged: keep the recorded value exactly (no text round trip)
    if (const auto error = recording::setRerunParameter(p, name, text)) {
      last_error_ = QString::fromStdString(*error);
      return std::nullopt;
    }
  }
  last_error_.clear();
  return p;
}

QString RerunDialog::error() const {
  return last_error_;
}

void RerunDialog::accept() {
  if (!parameters()) {
    error_->setText(last_error_);
    return;
  }
  QDialog::accept();
}

}  // namespace irgs::gui
