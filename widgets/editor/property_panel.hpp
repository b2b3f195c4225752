#pragma once
// Numeric editing of the editor's selection: id, coordinates and flags of one wall, obstacle,
// feature or the start pose (heading in degrees); centre, heading, size and colour of a ceiling
// marker; centre, orientation, length and width of a light; position and marker of a graph node;
// ends, direction and cost of a graph edge (the corridor length, computed from the nodes unless
// given); plus move-by and rotate-by for any selection. Every change becomes one undoable edit on
// the EditorModel; an invalid value (a taken id) is refused with a message and the fields show the
// map again.

#include <QWidget>

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QFormLayout;
class QLabel;
class QLayout;
class QLineEdit;
class QTableWidget;
class QTableWidgetItem;

namespace irgs::widgets {

class EditorModel;

class PropertyPanel : public QWidget {
  Q_OBJECT

 public:
  explicit PropertyPanel(EditorModel& model, QWidget* parent = nullptr);

  // Shows the model's selection again (called on selection and map changes).
  void refresh();

  // For tests: the widgets of the form.
  QLineEdit* idEdit() const { return id_; }
  QTableWidget* vertexTable() const { return vertices_; }
  QDoubleSpinBox* xSpin() const { return x_; }
  QDoubleSpinBox* ySpin() const { return y_; }
  QDoubleSpinBox* headingSpin() const { return heading_; }
  QCheckBox* closedCheck() const { return closed_; }
  QDoubleSpinBox* sizeSpin() const { return size_; }  // marker size, light length
  QDoubleSpinBox* widthSpin() const { return width_; }
  QLineEdit* colourEdit() const { return colour_; }
  QComboBox* markerCombo() const { return marker_; }  // node's marker ("" = none first)
  QCheckBox* bidirectionalCheck() const { return bidirectional_; }
  QCheckBox* costGivenCheck() const { return cost_given_; }
  QDoubleSpinBox* costSpin() const { return cost_; }
  QLabel* costLabel() const { return cost_label_; }
  QLabel* errorLabel() const { return error_; }
  // Applies the move-by / rotate-by fields to the selection.
  void applyMove(double dx_m, double dy_m);
  void applyRotate(double angle_deg);

 private:
  void commitId();
  void commitPoint();
  void commitVertex(QTableWidgetItem* item);
  void commitClosed(bool closed);
  void commitKind(int index);
  void commitCeilingOrGraph();
  void commitColour();
  void showError(const QString& text);

  EditorModel& model_;
  bool updating_ = false;  // true while refresh() fills the fields

  QLabel* title_ = nullptr;
  QWidget* single_ = nullptr;
  QLineEdit* id_ = nullptr;
  QComboBox* kind_ = nullptr;
  QCheckBox* closed_ = nullptr;
  QDoubleSpinBox* x_ = nullptr;
  QDoubleSpinBox* y_ = nullptr;
  QDoubleSpinBox* heading_ = nullptr;
  QTableWidget* vertices_ = nullptr;
  QDoubleSpinBox* size_ = nullptr;
  QDoubleSpinBox* width_ = nullptr;
  QLineEdit* colour_ = nullptr;
  QComboBox* marker_ = nullptr;
  QCheckBox* bidirectional_ = nullptr;
  QCheckBox* cost_given_ = nullptr;
  QDoubleSpinBox* cost_ = nullptr;
  QLayout* cost_row_ = nullptr;  // "Given" and the cost: one form row
  QLabel* cost_label_ = nullptr;
  QFormLayout* form_ = nullptr;
  QWidget* transform_ = nullptr;
  QDoubleSpinBox* move_dx_ = nullptr;
  QDoubleSpinBox* move_dy_ = nullptr;
  QDoubleSpinBox* rotate_ = nullptr;
  QLabel* error_ = nullptr;
};

}  // namespace irgs::widgets
