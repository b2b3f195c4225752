#include "widgets/editor/editor_panel.hpp"

#include <QAction>
#include <QActionGroup>
#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QEvent>
#include <QFileDialog>
#include <QFormLayout>
#include <QGridLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QImageReader>
#include <QLabel>
#include <QListWidget>
#include <QMessageBox>
#include <QSignalBlocker>
#include <QStyle>
#include <QToolButton>
#include <QUndoStack>
#include <QVBoxLayout>
#include <algorithm>
#include <filesystem>

#include "core/editing/floor_plan.hpp"
#include "core/editing/vectorise.hpp"
#include "core/world/ros_map.hpp"
#include "widgets/editor/editor_model.hpp"
#include "widgets/editor/property_panel.hpp"
#include "widgets/layout/scroll_column.hpp"

namespace irgs::widgets {
namespace {

struct ToolInfo {
  EditorTool tool;
  const char* label;
  const char* tip;
};

constexpr ToolInfo kTools[] = {
    {EditorTool::kSelect, "Select", "Select, move (drag) and edit vertices of the selection"},
    {EditorTool::kWall, "Wall",
     "Draw a wall: click points, double-click or Enter to finish; "
     "click the first point to close the outline"},
    {EditorTool::kPolygon, "Obstacle",
     "Draw a polygon obstacle: click at least three points, "
     "double-click or Enter to finish"},
    {EditorTool::kStart, "Start pose", "Press at the start position, drag for the heading"},
    {EditorTool::kCorner, "Corner", "Place a corner (concave) feature"},
    {EditorTool::kEdge, "Edge", "Place an edge (convex) feature"},
    {EditorTool::kCeilingMarker, "Marker",
     "Place a ceiling marker: press at its centre, drag for its heading"},
    {EditorTool::kCeilingLight, "Light",
     "Draw a ceiling light: drag from one end of the tube to "
     "the other"},
    {EditorTool::kGraphNode, "Node",
     "Place a graph node; on a ceiling marker it is tied to the marker, at its centre"},
    {EditorTool::kGraphEdge, "Graph edge", "Join two graph nodes: click one, then the other"},
    {EditorTool::kCalibrate, "Calibrate",
     "Calibrate the floor plan: click two points of the image whose true distance (and the "
     "first one's position) you enter below"},
    {EditorTool::kMeasure, "Measure", "Drag to measure a distance and heading"},
};

QToolButton* button(QAction* action, QWidget* parent) {
  auto* b = new QToolButton(parent);
  b->setDefaultAction(action);
  b->setToolButtonStyle(Qt::ToolButtonTextOnly);
  b->setSizePolicy(QSizePolicy::Expanding, QSizePolicy::Fixed);
  return b;
}

}  // namespace

EditorPanel::EditorPanel(EditorModel& model, EditorLayer& layer, QWidget* parent)
    : QWidget(parent), model_(model), layer_(layer) {
  setObjectName(QStringLiteral("editorPanel"));
  // Taller than a laptop screen leaves the side column: it scrolls (ScrollColumn says why).
  auto* outer = new QVBoxLayout(this);
  outer->setContentsMargins(0, 0, 0, 0);
  auto* scroll = new ScrollColumn(this);
  scroll->setObjectName(QStringLiteral("editorScroll"));
  outer->addWidget(scroll);
  QVBoxLayout* layout = &scroll->column();

  // Tools.
  auto* tools_box = new QGroupBox(tr("Tools"), this);
  auto* tools_grid = new QGridLayout(tools_box);
  tools_grid->setSpacing(4);
  tool_group_ = new QActionGroup(this);
  int i = 0;
  for (const ToolInfo& info : kTools) {
    auto* action = new QAction(tr(info.label), this);
    action->setToolTip(tr(info.tip));
    action->setStatusTip(tr(info.tip));
    action->setCheckable(true);
    action->setObjectName(QStringLiteral("editorTool") +
                          QString::fromLatin1(info.label).remove(QLatin1Char(' ')));
    tool_group_->addAction(action);
    const EditorTool tool = info.tool;
    connect(action, &QAction::triggered, this, [this, tool] { layer_.setTool(tool); });
    tools_[tool] = action;
    tools_grid->addWidget(button(action, tools_box), i / 4, i % 4);
    ++i;
  }
  tools_.at(layer_.tool())->setChecked(true);
  connect(&layer_, &EditorLayer::toolChanged, this,
          [this](EditorTool tool) { tools_.at(tool)->setChecked(true); });
  layout->addWidget(tools_box);

  // Edit actions.
  undo_ = model_.undoStack().createUndoAction(this, tr("Undo"));
  undo_->setShortcut(QKeySequence::Undo);
  redo_ = model_.undoStack().createRedoAction(this, tr("Redo"));
  redo_->setShortcut(QKeySequence::Redo);
  copy_ = new QAction(tr("Copy"), this);
  copy_->setShortcut(QKeySequence::Copy);
  paste_ = new QAction(tr("Paste"), this);
  paste_->setShortcut(QKeySequence::Paste);
  delete_ = new QAction(tr("Delete"), this);
  delete_->setShortcut(QKeySequence::Delete);
  // The keys work while the canvas layer or this panel has the focus (not in other tabs).
  for (QAction* a : {undo_, redo_, copy_, paste_, delete_}) {
    a->setShortcutContext(Qt::WidgetWithChildrenShortcut);
    layer_.addAction(a);
    addAction(a);
  }
  connect(copy_, &QAction::triggered, &model_, [this] {
    model_.copySelection();
    updateActions();
  });
  connect(paste_, &QAction::triggered, &model_, [this] { model_.paste(pasteOffset()); });
  connect(delete_, &QAction::triggered, &model_, &EditorModel::deleteSelection);
  auto* edit_row = new QHBoxLayout;
  for (QAction* a : {undo_, redo_, copy_, paste_, delete_}) {
    QToolButton* b = button(a, this);
    b->setToolButtonStyle(Qt::ToolButtonTextOnly);
    edit_row->addWidget(b);
  }
  layout->addLayout(edit_row);
  vectorise_ = new QAction(tr("Vectorise Raster to Walls"), this);
  vectorise_->setToolTip(
      tr("Trace the raster layer's occupied regions (a ROS map) into closed walls"));
  connect(vectorise_, &QAction::triggered, &model_, [this] {
    model_.tryApply([](const WorldMap& map) { return editing::vectoriseRaster(map); });
  });
  import_raster_ = new QAction(tr("Import ROS Map as Raster…"), this);
  import_raster_->setToolTip(tr("Put a ROS map_server map (.yaml + image) under the vectors"));
  connect(import_raster_, &QAction::triggered, this, [this] {
    const QString path = QFileDialog::getOpenFileName(this, tr("Import ROS Map as Raster"), {},
                                                      tr("ROS maps (*.yaml *.yml)"));
    if (path.isEmpty())
      return;
    const QString problem = importRaster(path);
    if (!problem.isEmpty())
      QMessageBox::warning(this, tr("Import ROS Map"), problem);
  });
  auto* raster_row = new QHBoxLayout;
  for (QAction* a : {import_raster_, vectorise_}) {
    QToolButton* b = button(a, this);
    b->setToolButtonStyle(Qt::ToolButtonTextOnly);
    raster_row->addWidget(b);
  }
  layout->addLayout(raster_row);
  connect(&model_, &EditorModel::mapChanged, this, &EditorPanel::updateActions);

  // Floor plan: open beside the raster import; remove, opacity and the calibration values the
  // Calibrate tool applies show only while there is a plan (the tab stays as short as before).
  open_plan_ = new QAction(tr("Floor Plan…"), this);
  open_plan_->setToolTip(tr("Put an image (a drawing of the floor) under the map"));
  remove_plan_ = new QAction(tr("Remove Plan"), this);
  connect(open_plan_, &QAction::triggered, this, [this] {
    const QString path = QFileDialog::getOpenFileName(
        this, tr("Floor Plan"), {}, tr("Images (*.png *.jpg *.jpeg *.bmp *.pgm *.tif *.tiff)"));
    if (path.isEmpty())
      return;
    const QString problem = openFloorPlan(path);
    if (!problem.isEmpty())
      QMessageBox::warning(this, tr("Floor Plan"), problem);
  });
  connect(remove_plan_, &QAction::triggered, &model_, [this] {
    model_.tryApply([](const WorldMap& map) { return editing::setFloorPlan(map, std::nullopt); });
  });
  raster_row->insertWidget(0, button(open_plan_, this));
  plan_widget_ = new QWidget(this);
  auto* plan_grid = new QGridLayout(plan_widget_);
  plan_grid->setContentsMargins(0, 0, 0, 0);
  auto spin = [this](double lo, double hi, double value) {
    auto* s = new QDoubleSpinBox(plan_widget_);
    s->setRange(lo, hi);
    s->setDecimals(3);
    s->setSuffix(QStringLiteral(" m"));
    s->setValue(value);
    return s;
  };
  calib_distance_ = spin(0.001, 10000.0, 1.0);
  calib_x_ = spin(-100000.0, 100000.0, 0.0);
  calib_y_ = spin(-100000.0, 100000.0, 0.0);
  calib_distance_->setToolTip(tr("Calibrate tool: the true distance between the two points"));
  calib_x_->setToolTip(tr("Calibrate tool: where the first point truly is (x)"));
  calib_y_->setToolTip(tr("Calibrate tool: where the first point truly is (y)"));
  plan_opacity_ = new QDoubleSpinBox(plan_widget_);
  plan_opacity_->setRange(0.0, 1.0);
  plan_opacity_->setSingleStep(0.1);
  plan_opacity_->setDecimals(2);
  plan_opacity_->setKeyboardTracking(false);
  plan_opacity_->setPrefix(tr("opacity "));
  plan_grid->addWidget(button(remove_plan_, plan_widget_), 0, 0);
  plan_grid->addWidget(plan_opacity_, 0, 1);
  plan_grid->addWidget(new QLabel(tr("A–B"), plan_widget_), 0, 2);
  plan_grid->addWidget(calib_distance_, 0, 3);
  plan_grid->addWidget(new QLabel(tr("A at x, y"), plan_widget_), 1, 0);
  plan_grid->addWidget(calib_x_, 1, 1);
  plan_grid->addWidget(calib_y_, 1, 2, 1, 2);
  layout->addWidget(plan_widget_);
  connect(plan_opacity_, &QDoubleSpinBox::valueChanged, &model_, [this](double opacity) {
    if (!model_.map().floor_plan || model_.map().floor_plan->opacity == opacity)
      return;
    FloorPlan plan = *model_.map().floor_plan;
    plan.opacity = opacity;
    model_.tryApply([&](const WorldMap& map) {
      return editing::setFloorPlan(map, plan, "Floor plan opacity");
    });
  });
  connect(&layer_, &EditorLayer::calibrationStarted, this, [this](double x, double y) {
    calib_x_->setValue(x);
    calib_y_->setValue(y);
  });
  connect(&layer_, &EditorLayer::calibrationRequested, this, &EditorPanel::calibrate);

  // Snapping.
  auto* snap_box = new QGroupBox(tr("Snap"), this);
  auto* snap = new QGridLayout(snap_box);
  grid_ = new QCheckBox(tr("Grid"), snap_box);
  grid_->setChecked(model_.snapSettings().grid);
  grid_step_ = new QDoubleSpinBox(snap_box);
  grid_step_->setRange(0.01, 10.0);
  grid_step_->setDecimals(2);
  grid_step_->setSingleStep(0.05);
  grid_step_->setSuffix(QStringLiteral(" m"));
  grid_step_->setValue(model_.snapSettings().grid_step_m);
  endpoints_ = new QCheckBox(tr("Endpoints"), snap_box);
  endpoints_->setChecked(model_.snapSettings().endpoints);
  angle_ = new QComboBox(snap_box);
  angle_->addItem(tr("Any angle"), 0.0);
  angle_->addItem(QStringLiteral("15°"), 15.0);
  angle_->addItem(QStringLiteral("45°"), 45.0);
  angle_->addItem(QStringLiteral("90°"), 90.0);
  angle_->setCurrentIndex(2);
  snap->addWidget(grid_, 0, 0);
  snap->addWidget(grid_step_, 0, 1);
  snap->addWidget(endpoints_, 1, 0, 1, 2);
  snap->addWidget(new QLabel(tr("Angles from the last point"), snap_box), 2, 0);
  snap->addWidget(angle_, 2, 1);
  layout->addWidget(snap_box);
  connect(grid_, &QCheckBox::toggled, this, &EditorPanel::updateSnap);
  connect(grid_step_, &QDoubleSpinBox::valueChanged, this, &EditorPanel::updateSnap);
  connect(endpoints_, &QCheckBox::toggled, this, &EditorPanel::updateSnap);
  connect(angle_, &QComboBox::currentIndexChanged, this, &EditorPanel::updateSnap);
  updateSnap();

  // Selection properties.
  auto* props_box = new QGroupBox(tr("Selection"), this);
  auto* props_layout = new QVBoxLayout(props_box);
  properties_ = new PropertyPanel(model_, props_box);
  props_layout->addWidget(properties_);
  layout->addWidget(props_box, 1);

  // Validation.
  issue_title_ = new QLabel(this);
  layout->addWidget(issue_title_);
  issues_ = new QListWidget(this);
  issues_->setObjectName(QStringLiteral("editorIssues"));
  issues_->setWordWrap(true);
  issues_->setMaximumHeight(110);
  layout->addWidget(issues_);
  connect(issues_, &QListWidget::itemClicked, this, [this](QListWidgetItem* item) {
    const int row = issues_->row(item);
    const auto& list = model_.issues();
    if (row < 0 || row >= static_cast<int>(list.size()))
      return;
    const editing::MapIssue& issue = list[static_cast<std::size_t>(row)];
    model_.setSelection(issue.elements);
    emit issueActivated(issue.position.x(), issue.position.y());
  });
  connect(&model_, &EditorModel::issuesChanged, this, &EditorPanel::refreshIssues);
  connect(&model_, &EditorModel::selectionChanged, this, &EditorPanel::updateActions);
  refreshIssues();
  updateActions();
}

Vec2 EditorPanel::pasteOffset() const {
  const double step = std::max(grid_step_->value(), 0.1);
  return {step, -step};
}

void EditorPanel::updateSnap() {
  editing::SnapSettings s = model_.snapSettings();
  s.grid = grid_->isChecked();
  s.grid_step_m = grid_step_->value();
  s.endpoints = endpoints_->isChecked();
  s.angle_step_rad = degToRad(angle_->currentData().toDouble());
  grid_step_->setEnabled(s.grid);
  model_.setSnapSettings(s);
}

void EditorPanel::refreshIssues() {
  issues_->clear();
  const auto& list = model_.issues();
  int errors = 0;
  for (const editing::MapIssue& issue : list) {
    auto* item = new QListWidgetItem(QString::fromStdString(issue.message), issues_);
    const bool error = issue.severity == Severity::kError;
    errors += error ? 1 : 0;
    item->setForeground(error ? QColor(176, 0, 32) : QColor(150, 95, 0));
  }
  issue_title_->setText(
      list.empty() ? tr("Validation: no issues")
                   : tr("Validation: %1 issue(s), %2 error(s)").arg(list.size()).arg(errors));
  issues_->setVisible(!list.empty());
}

QString EditorPanel::importRaster(const QString& yaml_path) {
  const std::filesystem::path path = yaml_path.toStdString();
  const RosMapLoadResult loaded = loadRosMap(path);
  if (!loaded.raster) {
    QStringList lines;
    for (const Diagnostic& d : loaded.diagnostics)
      lines << QString::fromStdString(d.toString());
    return lines.isEmpty() ? tr("%1 could not be read").arg(yaml_path)
                           : lines.join(QLatin1Char('\n'));
  }
  RasterLayer layer;
  layer.source = path.filename().string();
  layer.raster = *loaded.raster;
  std::error_code ec;
  const std::filesystem::path absolute = std::filesystem::absolute(path, ec);
  layer.resolved_path = ec ? path.string() : absolute.lexically_normal().string();
  QString problem;
  const QMetaObject::Connection listen = connect(&model_, &EditorModel::rejected, this,
                                                 [&problem](const QString& why) { problem = why; });
  const bool applied = model_.tryApply(
      [&layer](const WorldMap& map) { return editing::setRasterLayer(map, std::move(layer)); });
  disconnect(listen);
  if (!applied)
    return problem.isEmpty() ? tr("the raster layer was not imported") : problem;
  return {};
}

QString EditorPanel::openFloorPlan(const QString& image_path) {
  QImageReader reader(image_path);
  const QSize size = reader.size();
  if (!reader.canRead() || !size.isValid())
    return tr("%1 is not an image IRGS can read").arg(image_path);
  const std::filesystem::path path = image_path.toStdString();
  FloorPlan plan;
  plan.source = path.filename().string();
  std::error_code ec;
  const std::filesystem::path absolute = std::filesystem::absolute(path, ec);
  plan.resolved_path = ec ? path.string() : absolute.lexically_normal().string();
  plan.metres_per_pixel = 0.02;
  // The image's top-left corner at the map's, until it is calibrated.
  const Box2 box = model_.map().bounds();
  plan.origin = box.empty() ? Vec2(0.0, size.height() * plan.metres_per_pixel)
                            : Vec2(box.min.x(), box.max.y());
  QString problem;
  const QMetaObject::Connection listen = connect(&model_, &EditorModel::rejected, this,
                                                 [&problem](const QString& why) { problem = why; });
  const bool applied = model_.tryApply(
      [&plan](const WorldMap& map) { return editing::setFloorPlan(map, plan, "Open floor plan"); });
  disconnect(listen);
  if (!applied)
    return problem.isEmpty() ? tr("the floor plan was not opened") : problem;
  layer_.setTool(EditorTool::kCalibrate);
  return {};
}

void EditorPanel::calibrate(QPointF pixel_a, QPointF pixel_b) {
  if (!model_.map().floor_plan)
    return;
  const FloorPlan& plan = *model_.map().floor_plan;
  const Vec2 a(pixel_a.x(), pixel_a.y()), b(pixel_b.x(), pixel_b.y());
  // B keeps its direction from A (the rotation stays); A goes where the fields say.
  const Vec2 now = editing::floorPlanToWorld(plan, b) - editing::floorPlanToWorld(plan, a);
  if (now.norm() <= 0.0) {
    emit layer_.message(tr("Calibration: click two different points"));
    return;
  }
  const Vec2 world_a(calib_x_->value(), calib_y_->value());
  const Vec2 world_b = world_a + calib_distance_->value() * now.normalized();
  const std::optional<FloorPlan> calibrated =
      editing::calibrateFloorPlan(plan, a, b, world_a, world_b);
  if (!calibrated)
    return;
  model_.tryApply([&](const WorldMap& map) {
    return editing::setFloorPlan(map, calibrated, "Calibrate floor plan");
  });
  emit layer_.message(
      tr("Floor plan: %1 m per pixel").arg(calibrated->metres_per_pixel, 0, 'g', 4));
}

void EditorPanel::updateActions() {
  const bool any = !model_.selection().empty();
  copy_->setEnabled(any);
  delete_->setEnabled(any);
  paste_->setEnabled(model_.canPaste());
  if (vectorise_ != nullptr)
    vectorise_->setEnabled(model_.map().raster && !model_.map().raster->raster.empty());
  if (plan_widget_ != nullptr) {
    const bool plan = model_.map().floor_plan.has_value();
    remove_plan_->setEnabled(plan);
    plan_widget_->setVisible(plan);
    if (plan && plan_opacity_->value() != model_.map().floor_plan->opacity) {
      const QSignalBlocker block(plan_opacity_);
      plan_opacity_->setValue(model_.map().floor_plan->opacity);
    }
  }
}

}  // namespace irgs::widgets
