#pragma once
// File > Re-run with Parameters...: the parameters of a re-run (app/recording/
// rerun_parameters.hpp), prefilled with the recording's own, grouped as mapping and
// localization; a changed value is shown in bold and the recorded one stays beside it. OK checks
// every value (the reason of a refusal is shown in red and the dialog stays open).

#include <QDialog>
#include <QString>
#include <map>
#include <optional>
#include <string>

#include "app/recording/rerun_parameters.hpp"

class QComboBox;
class QLabel;
class QLineEdit;
class QWidget;

namespace irgs::gui {

class RerunDialog : public QDialog {
  Q_OBJECT

 public:
  RerunDialog(const QString& recording_name, const recording::RerunParameters& recorded,
              QWidget* parent = nullptr);

  // The value shown for `name` as text; setValue edits it as the user would.
  QString value(const std::string& name) const;
  void setValue(const std::string& name, const QString& text);
  void resetToRecorded();
  // The parameters as edited, or nothing with the reason in error().
  std::optional<recording::RerunParameters> parameters() const;
  QString error() const;

  void accept() override;

 private:
  struct Editor {
    QLineEdit* line = nullptr;   // numbers
    QComboBox* combo = nullptr;  // choices
  };
  void markChanged(const std::string& name);

  recording::RerunParameters recorded_;
  std::map<std::string, Editor> editors_;
  QLabel* error_ = nullptr;
  mutable QString last_error_;
};

}  // namespace irgs::gui
