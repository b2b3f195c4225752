#pragma once
// The robot-link part of the main window: the command panel's Simulator / Robot link switch
// (choosing the link opens the connection dialog), the link-health panel, the link state in the
// status bar, the behaviour buttons, and in the settings the last URL and the MAVLink signing
// choice and key (applied to every connection). MainWindow lays the health panel out;
// everything else about the link is wired here.

#include <QObject>
#include <QString>
#include <functional>
#include <optional>

#include "widgets/link/connection_dialog.hpp"

class QLabel;
class QSettings;
class QStatusBar;
class QWidget;

namespace irgs::widgets {
class CommandPanel;
class LinkHealthPanel;
struct LinkHealth;
}  // namespace irgs::widgets

namespace irgs::gui {

class LinkController;
class SessionController;

inline constexpr char kLastLinkUrlKey[] = "link/lastUrl";

class LinkUi : public QObject {
  Q_OBJECT

 public:
  // Shows the connection dialog and returns the chosen URL, or nothing when cancelled. The
  // default runs widgets::ConnectionDialog modally; tests replace it.
  using DialogRunner = std::function<std::optional<QString>(widgets::ConnectionDialogOptions)>;

  // `dialog_parent` parents the dialog and the health panel (which the caller lays out).
  LinkUi(SessionController& session, QSettings& settings, widgets::CommandPanel& panel,
         QStatusBar& status_bar, QWidget& dialog_parent);
  ~LinkUi() override;

  LinkController& controller() const { return *controller_; }
  widgets::LinkHealthPanel& healthPanel() const { return *health_panel_; }
  QLabel& statusLabel() const { return *status_label_; }
  void setDialogRunner(DialogRunner runner);

  // Connects to `url` (command line, dialog); reports a refusal in the console and returns it.
  QString connectTo(const QString& url);
  // Asks for a URL with the dialog and connects; false when cancelled or refused.
  bool chooseAndConnect();
  void backToSimulator();

  // The signing choice kept in the settings (what the dialog's Connect saves), and saving one.
  widgets::SigningChoice signingChoice() const;
  void saveSigningChoice(const widgets::SigningChoice& choice);
  // The key tools the connection dialog gets (comms' key format, fingerprint, random keys).
  static widgets::SigningKeyTools signingKeyTools();

 private:
  void onModeRequested(int mode);
  void onLinkedChanged(bool linked);
  void onHealthChanged(const widgets::LinkHealth& health);
  void applySigning();                     // the saved choice, to the links connectTo() opens
  void reportSigning(const QString& url);  // says in the console whether the link is signed

  SessionController& session_;
  QSettings& settings_;
  widgets::CommandPanel& panel_;
  QWidget& dialog_parent_;
  LinkController* controller_ = nullptr;
  widgets::LinkHealthPanel* health_panel_ = nullptr;
  QLabel* status_label_ = nullptr;
  DialogRunner dialog_runner_;
};

}  // namespace irgs::gui
