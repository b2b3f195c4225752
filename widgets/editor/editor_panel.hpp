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
  // Puts the image at `image_path` under the map as its floor plan (2 cm per pixel, its top-left
  // corner at the map's), one undoable step. Returns the problem ("" on success).
  QString openFloorPlan(const QString& image_path);
  QAction* floorPlanAction() const { return open_plan_; }
  QAction* removeFloorPlanAction() const { return remove_plan_; }
  // Calibration (the Calibrate tool's two clicks): the true distance between the points, m, and
  // where the first point truly is (filled with where it is now when it is clicked).
  QDoubleSpinBox& calibrationDistance() const { return *calib_distance_; }
  QDoubleSpinBox& calibrationX() const { return *calib_x_; }
  QDoubleSpinBox& calibrationY() const { return *calib_y_; }
  QDoubleSpinBox& floorPlanOpacity() const { return *plan_opacity_; }
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
  void calibrate(QPointF pixel_a, QPointF pixel_b);

  EditorModel& model_;
  EditorLayer& layer_;
  std::map<EditorTool, QAction*> tools_;
  QActionGroup* tool_group_ = nullptr;
  QAction* undo_ = nullptr;
  QAction* redo_ = nullptr;
  QAction* vectorise_ = nullptr;
  QAction* import_raster_ = nullptr;
  QAction* open_plan_ = nullptr;
  QAction* remove_plan_ = nullptr;
  QDoubleSpinBox* calib_distance_ = nullptr;
  QDoubleSpinBox* calib_x_ = nullptr;
  QDoubleSpinBox* calib_y_ = nullptr;
  QDoubleSpinBox* plan_opacity_ = nullptr;
  QWidget* plan_widget_ = nullptr;  // remove, opacity, calibration: shown with a plan
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
