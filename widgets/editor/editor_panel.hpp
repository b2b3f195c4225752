#pragma once
// The side panel of the map editor: tool buttons, snap settings, undo/redo, clipboard and
// delete, the property panel for the selection and the list of validation issues (a click
// selects the elements involved).

#include <QWidget>
#include <map>

#include "widgets/editor/editor_layer.hpp"

class QAction;
class QActionGroup;
class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QListWidget;

namespace irgs::widgets {

class EditorModel;
class PropertyPanel;

class EditorPanel : public QWidget {
  Q_OBJECT

 public:
  EditorPanel(EditorModel& model, EditorLayer& layer, QWidget* parent = nullptr);

  QAction* toolAction(EditorTool tool) const { return tools_.at(tool); }
  QAction* undoAction() const { return undo_; }
  QAction* redoAction() const { return redo_; }
  QAction* copyAction() const { return copy_; }
  QAction* pasteAction() const { return paste_; }
  QAction* deleteAction() const { return delete_; }
  // Adds the raster layer's occupied outlines as closed walls (core/editing/vectorise.hpp), one
  // undoable step; enabled while the map has a raster layer.
  QAction* vectoriseAction() const { return vectorise_; }
  // Opens a file dialog for a ROS map (.yaml) and imports it as the raster layer.
  QAction* importRasterAction() const { return import_raster_; }
  // Imports the ROS map at `yaml_path` as the map's raster layer (replacing any), one undoable
  // step. Returns the problem ("" on success); the action shows it in a message box.
  QString importRaster(const QString& yaml_path);
  PropertyPanel& properties() const { return *properties_; }
  QListWidget& issueList() const { return *issues_; }
  QCheckBox& gridCheck() const { return *grid_; }
  QDoubleSpinBox& gridStep() const { return *grid_step_; }
  QCheckBox& endpointCheck() const { return *endpoints_; }
  QComboBox& angleCombo() const { return *angle_; }

  // Paste offset: copies land this far from the originals, m (one grid step by default).
  irgs::Vec2 pasteOffset() const;

 signals:
  // A validation issue was clicked: its position, for the view to centre on.
  void issueActivated(double x_m, double y_m);

 private:
  void updateSnap();
  void refreshIssues();
  void updateActions();

  EditorModel& model_;
  EditorLayer& layer_;
  std::map<EditorTool, QAction*> tools_;
  QActionGroup* tool_group_ = nullptr;
  QAction* undo_ = nullptr;
  QAction* redo_ = nullptr;
  QAction* vectorise_ = nullptr;
  QAction* import_raster_ = nullptr;
  QAction* copy_ = nullptr;
  QAction* paste_ = nullptr;
  QAction* delete_ = nullptr;
  QCheckBox* grid_ = nullptr;
  QDoubleSpinBox* grid_step_ = nullptr;
  QCheckBox* endpoints_ = nullptr;
  QComboBox* angle_ = nullptr;
  PropertyPanel* properties_ = nullptr;
  QLabel* issue_title_ = nullptr;
  QListWidget* issues_ = nullptr;
};

}  // namespace irgs::widgets
