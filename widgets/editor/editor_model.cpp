#include "widgets/editor/editor_model.hpp"

#include <QUndoCommand>
#include <algorithm>
#include <stdexcept>
#include <utility>

namespace irgs::widgets {

using editing::Edit;
using editing::ElementRef;

// One core edit on the undo stack. redo() applies it (QUndoStack::push calls redo), undo()
// reverts it; each restores the selection that belongs to its side of the edit.
class EditCommand : public QUndoCommand {
 public:
  EditCommand(EditorModel& model, Edit edit, std::vector<ElementRef> selection_before)
      : QUndoCommand(QString::fromStdString(edit.label)),
        model_(model),
        edit_(std::move(edit)),
        selection_before_(std::move(selection_before)) {}

  void redo() override {
    editing::applyEdit(model_.map_, edit_);
    model_.afterChange(edit_.selection_after);
  }
  void undo() override {
    editing::revertEdit(model_.map_, edit_);
    model_.afterChange(selection_before_);
  }

 private:
  EditorModel& model_;
  Edit edit_;
  std::vector<ElementRef> selection_before_;
};

EditorModel::EditorModel(QObject* parent) : QObject(parent) {
  undo_.setUndoLimit(0);  // unlimited: edits hold elements, not whole maps
  revalidate();
}

EditorModel::~EditorModel() {
  // Commands refer to this model; drop them before the members go.
  undo_.clear();
}

void EditorModel::setMap(WorldMap map) {
  undo_.clear();
  map_ = std::move(map);
  selection_.clear();
  revalidate();
  emit mapChanged();
  emit selectionChanged();
}

bool EditorModel::apply(Edit edit) {
  if (edit.empty())
    return false;
  // Check that the edit fits before it reaches the stack (push runs redo, which must not throw).
  try {
    editing::applyEdit(map_, edit);
    editing::revertEdit(map_, edit);
  } catch (const std::exception& e) {
    emit rejected(QString::fromUtf8(e.what()));
    return false;
  }
  undo_.push(new EditCommand(*this, std::move(edit), selection_));
  return true;
}

void EditorModel::afterChange(std::vector<ElementRef> selection) {
  selection.erase(std::remove_if(selection.begin(), selection.end(),
                                 [&](const ElementRef& r) { return !isValidRef(map_, r); }),
                  selection.end());
  selection_ = std::move(selection);
  revalidate();
  emit mapChanged();
  emit selectionChanged();
}

void EditorModel::setSelection(std::vector<ElementRef> selection) {
  std::sort(selection.begin(), selection.end());
  selection.erase(std::unique(selection.begin(), selection.end()), selection.end());
  selection.erase(std::remove_if(selection.begin(), selection.end(),
                                 [&](const ElementRef& r) { return !isValidRef(map_, r); }),
                  selection.end());
  if (selection == selection_)
    return;
  selection_ = std::move(selection);
  emit selectionChanged();
}

bool EditorModel::isSelected(const ElementRef& ref) const {
  return std::find(selection_.begin(), selection_.end(), ref) != selection_.end();
}

void EditorModel::copySelection() {
  editing::Clipboard copied = editing::copyElements(map_, selection_);
  if (!copied.empty())
    clipboard_ = std::move(copied);
}

void EditorModel::paste(const Vec2& offset) {
  if (clipboard_.empty())
    return;
  tryApply([&](const WorldMap& m) { return editing::pasteElements(m, clipboard_, offset); });
}

void EditorModel::deleteSelection() {
  tryApply([&](const WorldMap& m) { return editing::deleteElements(m, selection_); });
}

void EditorModel::rotateSelection(double angle_rad) {
  if (selection_.empty())
    return;
  const Vec2 pivot = editing::selectionCentre(map_, selection_);
  tryApply(
      [&](const WorldMap& m) { return editing::rotateElements(m, selection_, angle_rad, pivot); });
}

void EditorModel::setSnapSettings(const editing::SnapSettings& settings) {
  if (!(settings.grid_step_m > 0.0) || !(settings.endpoint_radius_m >= 0.0) ||
      !(settings.angle_step_rad >= 0.0))
    throw std::invalid_argument("EditorModel::setSnapSettings: invalid settings");
  snap_ = settings;
  emit snapSettingsChanged();
}

void EditorModel::setValidationSettings(const editing::ValidationSettings& settings) {
  validation_ = settings;
  revalidate();
}

void EditorModel::revalidate() {
  issues_ = editing::validateMap(map_, validation_);
  emit issuesChanged();
}

}  // namespace irgs::widgets
