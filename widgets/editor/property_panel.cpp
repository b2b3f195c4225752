#include "widgets/editor/property_panel.hpp"

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QTableWidget>
#include <QVBoxLayout>
#include <algorithm>
#include <cmath>
#include <optional>
#include <type_traits>
#include <variant>

#include "widgets/editor/editor_model.hpp"

namespace irgs::widgets {

using editing::Element;
using editing::ElementKind;
using editing::ElementRef;

namespace {

constexpr double kCoordinateLimit_m = 100000.0;

QDoubleSpinBox* coordinateSpin(QWidget* parent, const QString& suffix = QStringLiteral(" m")) {
  auto* spin = new QDoubleSpinBox(parent);
  spin->setRange(-kCoordinateLimit_m, kCoordinateLimit_m);
  spin->setDecimals(3);
  spin->setSingleStep(0.05);
  spin->setSuffix(suffix);
  spin->setKeyboardTracking(false);
  spin->setAccelerated(true);
  return spin;
}

std::vector<Vec2>* pointsIn(Element& e) {
  if (auto* w = std::get_if<Wall>(&e))
    return &w->points;
  if (auto* o = std::get_if<Obstacle>(&e))
    return &o->polygon;
  return nullptr;
}

}  // namespace

PropertyPanel::PropertyPanel(EditorModel& model, QWidget* parent) : QWidget(parent), model_(model) {
  setObjectName(QStringLiteral("propertyPanel"));
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  title_ = new QLabel(this);
  title_->setObjectName(QStringLiteral("propertyTitle"));
  QFont bold = title_->font();
  bold.setBold(true);
  title_->setFont(bold);
  layout->addWidget(title_);

  single_ = new QWidget(this);
  form_ = new QFormLayout(single_);
  form_->setContentsMargins(0, 0, 0, 0);
  id_ = new QLineEdit(single_);
  id_->setObjectName(QStringLiteral("propertyId"));
  form_->addRow(tr("Id"), id_);
  kind_ = new QComboBox(single_);
  kind_->addItem(tr("Corner (concave)"));
  kind_->addItem(tr("Edge (convex)"));
  form_->addRow(tr("Kind"), kind_);
  closed_ = new QCheckBox(tr("Closed outline"), single_);
  form_->addRow(QString(), closed_);
  x_ = coordinateSpin(single_);
  y_ = coordinateSpin(single_);
  x_->setObjectName(QStringLiteral("propertyX"));
  y_->setObjectName(QStringLiteral("propertyY"));
  form_->addRow(tr("x"), x_);
  form_->addRow(tr("y"), y_);
  heading_ = new QDoubleSpinBox(single_);
  heading_->setRange(-180.0, 180.0);
  heading_->setDecimals(1);
  heading_->setWrapping(true);
  heading_->setSuffix(QStringLiteral("°"));
  heading_->setKeyboardTracking(false);
  heading_->setObjectName(QStringLiteral("propertyHeading"));
  form_->addRow(tr("Heading"), heading_);
  size_ = coordinateSpin(single_);
  size_->setRange(0.001, 1000.0);
  size_->setObjectName(QStringLiteral("propertySize"));
  form_->addRow(tr("Size"), size_);
  width_ = coordinateSpin(single_);
  width_->setRange(0.001, 100.0);
  width_->setObjectName(QStringLiteral("propertyWidth"));
  form_->addRow(tr("Width"), width_);
  colour_ = new QLineEdit(single_);
  colour_->setObjectName(QStringLiteral("propertyColour"));
  colour_->setPlaceholderText(QStringLiteral("#rrggbb"));
  colour_->setToolTip(
      tr("The marker's colour as #rrggbb; the detector looks for the default red "
         "(#ff293d), other colours are painted squares it ignores"));
  form_->addRow(tr("Colour"), colour_);
  marker_ = new QComboBox(single_);
  marker_->setObjectName(QStringLiteral("propertyMarker"));
  marker_->setToolTip(tr("The ceiling marker at this node"));
  form_->addRow(tr("Marker"), marker_);
  bidirectional_ = new QCheckBox(tr("Both directions"), single_);
  form_->addRow(QString(), bidirectional_);
  auto* cost_row = new QHBoxLayout;
  cost_given_ = new QCheckBox(tr("Given"), single_);
  cost_given_->setToolTip(
      tr("Give the corridor length (a corridor that bends); otherwise it is "
         "the straight distance between the nodes"));
  cost_ = coordinateSpin(single_);
  cost_->setRange(0.001, kCoordinateLimit_m);
  cost_->setObjectName(QStringLiteral("propertyCost"));
  cost_row->addWidget(cost_given_);
  cost_row->addWidget(cost_, 1);
  form_->addRow(tr("Cost"), cost_row);
  cost_row_ = cost_row;
  cost_label_ = new QLabel(single_);
  cost_label_->setObjectName(QStringLiteral("propertyCostLabel"));
  // No word wrap: a height-for-width label in a form with hidden rows overruns a buffer in
  // QFormLayout (Qt 6.4, seen under valgrind); the texts are short instead.
  form_->addRow(QString(), cost_label_);
  vertices_ = new QTableWidget(0, 2, single_);
  vertices_->setObjectName(QStringLiteral("propertyVertices"));
  vertices_->setHorizontalHeaderLabels({tr("x (m)"), tr("y (m)")});
  vertices_->horizontalHeader()->setSectionResizeMode(QHeaderView::Stretch);
  vertices_->verticalHeader()->setDefaultSectionSize(22);
  vertices_->setMinimumHeight(90);
  form_->addRow(tr("Points"), vertices_);
  layout->addWidget(single_);

  transform_ = new QWidget(this);
  auto* tf = new QFormLayout(transform_);
  tf->setContentsMargins(0, 0, 0, 0);
  auto* move_row = new QHBoxLayout;
  move_dx_ = coordinateSpin(transform_);
  move_dy_ = coordinateSpin(transform_);
  move_dx_->setPrefix(QStringLiteral("Δx "));
  move_dy_->setPrefix(QStringLiteral("Δy "));
  auto* move_button = new QPushButton(tr("Move"), transform_);
  move_row->addWidget(move_dx_);
  move_row->addWidget(move_dy_);
  move_row->addWidget(move_button);
  tf->addRow(tr("Move by"), move_row);
  auto* rotate_row = new QHBoxLayout;
  rotate_ = new QDoubleSpinBox(transform_);
  rotate_->setRange(-360.0, 360.0);
  rotate_->setDecimals(1);
  rotate_->setValue(90.0);
  rotate_->setSuffix(QStringLiteral("°"));
  auto* rotate_button = new QPushButton(tr("Rotate"), transform_);
  rotate_row->addWidget(rotate_);
  rotate_row->addWidget(rotate_button);
  tf->addRow(tr("Rotate by"), rotate_row);
  layout->addWidget(transform_);

  error_ = new QLabel(this);
  error_->setObjectName(QStringLiteral("propertyError"));
  error_->setStyleSheet(QStringLiteral("color: #b00020;"));
  error_->setWordWrap(true);
  layout->addWidget(error_);
  layout->addStretch(1);

  connect(id_, &QLineEdit::editingFinished, this, &PropertyPanel::commitId);
  connect(x_, &QDoubleSpinBox::valueChanged, this, &PropertyPanel::commitPoint);
  connect(y_, &QDoubleSpinBox::valueChanged, this, &PropertyPanel::commitPoint);
  connect(heading_, &QDoubleSpinBox::valueChanged, this, &PropertyPanel::commitPoint);
  connect(vertices_, &QTableWidget::itemChanged, this, &PropertyPanel::commitVertex);
  connect(closed_, &QCheckBox::toggled, this, &PropertyPanel::commitClosed);
  connect(kind_, &QComboBox::currentIndexChanged, this, &PropertyPanel::commitKind);
  for (QDoubleSpinBox* spin : {size_, width_, cost_})
    connect(spin, &QDoubleSpinBox::valueChanged, this, &PropertyPanel::commitCeilingOrGraph);
  connect(marker_, &QComboBox::currentIndexChanged, this, &PropertyPanel::commitCeilingOrGraph);
  connect(bidirectional_, &QCheckBox::toggled, this, &PropertyPanel::commitCeilingOrGraph);
  connect(cost_given_, &QCheckBox::toggled, this, &PropertyPanel::commitCeilingOrGraph);
  connect(colour_, &QLineEdit::editingFinished, this, &PropertyPanel::commitColour);
  connect(move_button, &QPushButton::clicked, this,
          [this] { applyMove(move_dx_->value(), move_dy_->value()); });
  connect(rotate_button, &QPushButton::clicked, this, [this] { applyRotate(rotate_->value()); });
  connect(&model_, &EditorModel::selectionChanged, this, &PropertyPanel::refresh);
  connect(&model_, &EditorModel::mapChanged, this, &PropertyPanel::refresh);
  connect(&model_, &EditorModel::rejected, this, &PropertyPanel::showError);
  refresh();
}

void PropertyPanel::refresh() {
  updating_ = true;
  error_->clear();
  const auto& sel = model_.selection();
  transform_->setVisible(!sel.empty());
  single_->setVisible(sel.size() == 1);
  if (sel.empty()) {
    title_->setText(tr("Nothing selected — click an element, or drag a box"));
  } else if (sel.size() > 1) {
    title_->setText(tr("%n elements selected", nullptr, static_cast<int>(sel.size())));
  } else {
    const ElementRef ref = sel.front();
    const Element e = editing::elementAt(model_.map(), ref);
    title_->setText(QString::fromStdString(editing::describe(e)));
    const ElementKind k = ref.kind;
    const bool has_id = k != ElementKind::kStart && k != ElementKind::kEdge;
    const bool point_like = k == ElementKind::kFeature || k == ElementKind::kStart ||
                            k == ElementKind::kMarker || k == ElementKind::kLight ||
                            k == ElementKind::kNode;
    const bool edge = k == ElementKind::kEdge;
    form_->setRowVisible(id_, has_id);
    form_->setRowVisible(kind_, k == ElementKind::kFeature);
    form_->setRowVisible(closed_, k == ElementKind::kWall);
    form_->setRowVisible(x_, point_like);
    form_->setRowVisible(y_, point_like);
    form_->setRowVisible(heading_, k == ElementKind::kStart || k == ElementKind::kMarker ||
                                       k == ElementKind::kLight);
    form_->setRowVisible(vertices_, k == ElementKind::kWall || k == ElementKind::kObstacle);
    form_->setRowVisible(size_, k == ElementKind::kMarker || k == ElementKind::kLight);
    form_->setRowVisible(width_, k == ElementKind::kLight);
    form_->setRowVisible(colour_, k == ElementKind::kMarker);
    form_->setRowVisible(marker_, k == ElementKind::kNode);
    form_->setRowVisible(bidirectional_, edge);
    form_->setRowVisible(cost_row_, edge);
    form_->setRowVisible(cost_label_, edge);
    form_->labelForField(heading_)->setProperty(
        "text", k == ElementKind::kLight ? tr("Orientation") : tr("Heading"));
    form_->labelForField(size_)->setProperty("text",
                                             k == ElementKind::kLight ? tr("Length") : tr("Size"));
    form_->labelForField(x_)->setProperty("text",
                                          k == ElementKind::kLight ? tr("Centre x") : tr("x"));
    form_->labelForField(y_)->setProperty("text",
                                          k == ElementKind::kLight ? tr("Centre y") : tr("y"));
    id_->setText(QString::fromStdString(editing::elementId(e)));
    if (const auto* f = std::get_if<PointFeature>(&e)) {
      kind_->setCurrentIndex(f->kind == PointFeatureKind::kCorner ? 0 : 1);
      x_->setValue(f->position.x());
      y_->setValue(f->position.y());
    } else if (const auto* s = std::get_if<Pose2>(&e)) {
      x_->setValue(s->x);
      y_->setValue(s->y);
      heading_->setValue(radToDeg(s->theta));
    } else if (const auto* m = std::get_if<CeilingMarker>(&e)) {
      x_->setValue(m->position.x());
      y_->setValue(m->position.y());
      heading_->setValue(radToDeg(m->heading_rad));
      size_->setValue(m->size_m);
      colour_->setText(QString::fromStdString(formatHexColour(m->colour)));
    } else if (const auto* l = std::get_if<CeilingLight>(&e)) {
      const Vec2 c = (l->tube.a + l->tube.b) / 2.0, d = l->tube.b - l->tube.a;
      x_->setValue(c.x());
      y_->setValue(c.y());
      heading_->setValue(radToDeg(std::atan2(d.y(), d.x())));
      size_->setValue(d.norm());
      width_->setValue(l->width_m);
    } else if (const auto* n = std::get_if<TopoNode>(&e)) {
      x_->setValue(n->position.x());
      y_->setValue(n->position.y());
      marker_->clear();
      marker_->addItem(tr("(none)"), QString());
      for (const CeilingMarker& cm : model_.map().markers)
        marker_->addItem(QString::fromStdString(cm.id), QString::fromStdString(cm.id));
      const int at = marker_->findData(QString::fromStdString(n->marker_id));
      marker_->setCurrentIndex(at < 0 ? 0 : at);
    } else if (const auto* ed = std::get_if<TopoEdge>(&e)) {
      bidirectional_->setChecked(ed->bidirectional);
      cost_given_->setChecked(ed->cost_m.has_value());
      cost_->setEnabled(ed->cost_m.has_value());
      const TopoNode* a = model_.map().graph.node(ed->from);
      const TopoNode* b = model_.map().graph.node(ed->to);
      const double chord = a && b ? (b->position - a->position).norm() : 0.0;
      cost_->setValue(ed->cost_m.value_or(std::max(chord, 0.001)));
      cost_label_->setText(ed->cost_m ? tr("Given; the nodes are %1 m apart").arg(chord, 0, 'f', 3)
                                      : tr("= %1 m between the nodes").arg(chord, 0, 'f', 3));
    } else {
      if (const auto* w = std::get_if<Wall>(&e))
        closed_->setChecked(w->closed);
      Element copy = e;
      const std::vector<Vec2>& pts = *pointsIn(copy);
      vertices_->setRowCount(static_cast<int>(pts.size()));
      for (int i = 0; i < static_cast<int>(pts.size()); ++i) {
        const Vec2& q = pts[static_cast<std::size_t>(i)];
        // Existing items are reused: refresh() may run inside their itemChanged signal.
        for (int c = 0; c < 2; ++c) {
          const QString text = QString::number(c == 0 ? q.x() : q.y(), 'f', 3);
          if (QTableWidgetItem* item = vertices_->item(i, c))
            item->setText(text);
          else
            vertices_->setItem(i, c, new QTableWidgetItem(text));
        }
      }
    }
  }
  updating_ = false;
}

void PropertyPanel::showError(const QString& text) {
  error_->setText(text);
}

void PropertyPanel::commitId() {
  if (updating_ || model_.selection().size() != 1)
    return;
  const ElementRef ref = model_.selection().front();
  Element e = editing::elementAt(model_.map(), ref);
  const std::string id = id_->text().trimmed().toStdString();
  if (id == editing::elementId(e))
    return;
  std::visit(
      [&](auto& element) {
        using T = std::decay_t<decltype(element)>;
        if constexpr (!std::is_same_v<T, Pose2> && !std::is_same_v<T, TopoEdge>)
          element.id = id;
      },
      e);
  if (!model_.tryApply(
          [&](const WorldMap& m) { return editing::replaceElement(m, ref, e, "Rename"); })) {
    const QString reason = error_->text();
    refresh();
    showError(reason);
  }
}

void PropertyPanel::commitPoint() {
  if (updating_ || model_.selection().size() != 1)
    return;
  const ElementRef ref = model_.selection().front();
  Element e = editing::elementAt(model_.map(), ref);
  if (auto* f = std::get_if<PointFeature>(&e)) {
    f->position = Vec2(x_->value(), y_->value());
  } else if (auto* s = std::get_if<Pose2>(&e)) {
    *s = Pose2{x_->value(), y_->value(), degToRad(heading_->value())};
  } else if (auto* m = std::get_if<CeilingMarker>(&e)) {
    m->position = Vec2(x_->value(), y_->value());
    m->heading_rad = degToRad(heading_->value());
  } else if (auto* n = std::get_if<TopoNode>(&e)) {
    n->position = Vec2(x_->value(), y_->value());
  } else if (std::holds_alternative<CeilingLight>(e)) {
    commitCeilingOrGraph();  // centre and orientation rebuild the tube
    return;
  } else {
    return;
  }
  model_.tryApply(
      [&](const WorldMap& m) { return editing::replaceElement(m, ref, e, "Edit position"); });
}

void PropertyPanel::commitCeilingOrGraph() {
  if (updating_ || model_.selection().size() != 1)
    return;
  const ElementRef ref = model_.selection().front();
  Element e = editing::elementAt(model_.map(), ref);
  if (auto* m = std::get_if<CeilingMarker>(&e)) {
    m->size_m = size_->value();
  } else if (auto* l = std::get_if<CeilingLight>(&e)) {
    const Vec2 c(x_->value(), y_->value());
    const double heading = degToRad(heading_->value());
    const Vec2 half = 0.5 * size_->value() * Vec2(std::cos(heading), std::sin(heading));
    l->tube = {c - half, c + half};
    l->width_m = width_->value();
  } else if (auto* n = std::get_if<TopoNode>(&e)) {
    n->marker_id = marker_->currentData().toString().toStdString();
    // Tying a node to a marker puts it on the marker's centre.
    for (const CeilingMarker& cm : model_.map().markers)
      if (!n->marker_id.empty() && cm.id == n->marker_id)
        n->position = cm.position;
  } else if (auto* ed = std::get_if<TopoEdge>(&e)) {
    ed->bidirectional = bidirectional_->isChecked();
    ed->cost_m = cost_given_->isChecked() ? std::optional<double>(cost_->value()) : std::nullopt;
  } else {
    return;
  }
  model_.tryApply([&](const WorldMap& m) { return editing::replaceElement(m, ref, e, "Edit"); });
}

void PropertyPanel::commitColour() {
  if (updating_ || model_.selection().size() != 1)
    return;
  const ElementRef ref = model_.selection().front();
  Element e = editing::elementAt(model_.map(), ref);
  auto* m = std::get_if<CeilingMarker>(&e);
  if (m == nullptr)
    return;
  const std::optional<ColourRgb> colour = parseHexColour(colour_->text().trimmed().toStdString());
  if (!colour) {
    refresh();
    showError(tr("“%1” is not a colour #rrggbb").arg(colour_->text()));
    return;
  }
  if (*colour == m->colour)
    return;
  m->colour = *colour;
  model_.tryApply(
      [&](const WorldMap& map) { return editing::replaceElement(map, ref, e, "Change colour"); });
}

void PropertyPanel::commitVertex(QTableWidgetItem* item) {
  if (updating_ || item == nullptr || model_.selection().size() != 1)
    return;
  const ElementRef ref = model_.selection().front();
  Element e = editing::elementAt(model_.map(), ref);
  std::vector<Vec2>* pts = pointsIn(e);
  const auto row = static_cast<std::size_t>(item->row());
  if (pts == nullptr || row >= pts->size())
    return;
  bool ok = false;
  const double v = item->text().trimmed().toDouble(&ok);
  if (!ok || !std::isfinite(v) || std::abs(v) > kCoordinateLimit_m) {
    refresh();
    showError(tr("“%1” is not a coordinate in metres").arg(item->text()));
    return;
  }
  (item->column() == 0 ? (*pts)[row].x() : (*pts)[row].y()) = v;
  model_.tryApply(
      [&](const WorldMap& m) { return editing::replaceElement(m, ref, e, "Edit vertex"); });
}

void PropertyPanel::commitClosed(bool closed) {
  if (updating_ || model_.selection().size() != 1)
    return;
  const ElementRef ref = model_.selection().front();
  Element e = editing::elementAt(model_.map(), ref);
  auto* w = std::get_if<Wall>(&e);
  if (w == nullptr || w->closed == closed)
    return;
  w->closed = closed;
  model_.tryApply([&](const WorldMap& m) {
    return editing::replaceElement(m, ref, e, closed ? "Close outline" : "Open outline");
  });
}

void PropertyPanel::commitKind(int index) {
  if (updating_ || model_.selection().size() != 1)
    return;
  const ElementRef ref = model_.selection().front();
  Element e = editing::elementAt(model_.map(), ref);
  auto* f = std::get_if<PointFeature>(&e);
  if (f == nullptr)
    return;
  f->kind = index == 0 ? PointFeatureKind::kCorner : PointFeatureKind::kEdge;
  model_.tryApply(
      [&](const WorldMap& m) { return editing::replaceElement(m, ref, e, "Change feature kind"); });
}

void PropertyPanel::applyMove(double dx_m, double dy_m) {
  const auto sel = model_.selection();
  model_.tryApply(
      [&](const WorldMap& m) { return editing::moveElements(m, sel, Vec2(dx_m, dy_m)); });
}

void PropertyPanel::applyRotate(double angle_deg) {
  model_.rotateSelection(degToRad(angle_deg));
}

}  // namespace irgs::widgets
