#pragma once
// The map being edited: a WorldMap, the QUndoStack of core edits applied to it, the selection,
// the clipboard, the snap settings and the validation issues. Every change goes through apply(),
// so every action is undoable; tools, the property panel and the app all share one model.

#include <QObject>
#include <QUndoStack>
#include <exception>
#include <vector>

#include "core/editing/map_edit.hpp"
#include "core/editing/snapping.hpp"
#include "core/editing/validation.hpp"
#include "core/world/world_map.hpp"

namespace irgs::widgets {

class EditorModel : public QObject {
  Q_OBJECT

 public:
  explicit EditorModel(QObject* parent = nullptr);
  ~EditorModel() override;

  // Starts a new document: clears the undo history, the selection and the modified state.
  void setMap(irgs::WorldMap map);
  const irgs::WorldMap& map() const { return map_; }
  QUndoStack& undoStack() { return undo_; }

  // Pushes the edit onto the undo stack (which applies it). Empty edits are ignored. Returns
  // false, changing nothing, when the edit does not fit the map.
  bool apply(irgs::editing::Edit edit);
  // Runs a builder and applies its edit; a builder's std::exception (invalid input) is caught
  // and reported through rejected(). Returns whether an edit was applied.
  template <class Builder>
  bool tryApply(Builder&& build) {
    try {
      return apply(build(map_));
    } catch (const std::exception& e) {
      emit rejected(QString::fromUtf8(e.what()));
      return false;
    }
  }

  const std::vector<irgs::editing::ElementRef>& selection() const { return selection_; }
  void setSelection(std::vector<irgs::editing::ElementRef> selection);
  bool isSelected(const irgs::editing::ElementRef& ref) const;

  void copySelection();
  bool canPaste() const { return !clipboard_.empty(); }
  // Pastes the clipboard shifted by `offset` (world metres) and selects the copies.
  void paste(const irgs::Vec2& offset);
  void deleteSelection();
  // Rotates the selection about its centre.
  void rotateSelection(double angle_rad);

  const irgs::editing::SnapSettings& snapSettings() const { return snap_; }
  void setSnapSettings(const irgs::editing::SnapSettings& settings);

  const std::vector<irgs::editing::MapIssue>& issues() const { return issues_; }
  void setValidationSettings(const irgs::editing::ValidationSettings& settings);

  // Unsaved edits: the undo stack is away from its clean state.
  bool isModified() const { return !undo_.isClean(); }
  void markSaved() { undo_.setClean(); }

 signals:
  void mapChanged();  // after every apply, undo and redo, and setMap
  void selectionChanged();
  void snapSettingsChanged();
  void issuesChanged();
  void rejected(const QString& reason);  // an edit that could not be made

 private:
  friend class EditCommand;
  void revalidate();
  void afterChange(std::vector<irgs::editing::ElementRef> selection);

  irgs::WorldMap map_;
  QUndoStack undo_;
  std::vector<irgs::editing::ElementRef> selection_;
  irgs::editing::Clipboard clipboard_;
  irgs::editing::SnapSettings snap_;
  irgs::editing::ValidationSettings validation_;
  std::vector<irgs::editing::MapIssue> issues_;
};

}  // namespace irgs::widgets
