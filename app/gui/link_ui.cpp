#include "app/gui/link_ui.hpp"

#include <QLabel>
#include <QSettings>
#include <QStatusBar>

#include "app/gui/app_settings.hpp"
#include "app/gui/link_controller.hpp"
#include "app/gui/link_format.hpp"
#include "app/gui/session_controller.hpp"
#include "comms/link/link_url.hpp"
#include "comms/mavlink/signing_key.hpp"
#include "comms/robot/arcos_robot.hpp"
#include "widgets/command/command_panel.hpp"
#include "widgets/link/link_health_panel.hpp"

namespace irgs::gui {
namespace {

std::optional<QString> runConnectionDialog(QWidget& parent,
                                           widgets::ConnectionDialogOptions options) {
  widgets::ConnectionDialog dialog(std::move(options), &parent);
  if (dialog.exec() != QDialog::Accepted)
    return std::nullopt;
  return dialog.url();
}

}  // namespace

LinkUi::LinkUi(SessionController& session, QSettings& settings, widgets::CommandPanel& panel,
               QStatusBar& status_bar, QWidget& dialog_parent)
    : QObject(&dialog_parent),
      session_(session),
      settings_(settings),
      panel_(panel),
      dialog_parent_(dialog_parent) {
  controller_ = new LinkController(session_, this);
  health_panel_ = new widgets::LinkHealthPanel(&dialog_parent_);
  health_panel_->hide();
  status_label_ = new QLabel(&status_bar);
  status_label_->setObjectName(QStringLiteral("linkStatus"));
  status_label_->setToolTip(tr("State of the robot link"));
  status_label_->hide();
  status_bar.addPermanentWidget(status_label_);
  dialog_runner_ = [this](widgets::ConnectionDialogOptions options) {
    return runConnectionDialog(dialog_parent_, std::move(options));
  };

  panel_.setLinkedModeAvailable(true, {});
  connect(&panel_, &widgets::CommandPanel::modeRequested, this,
          [this](widgets::RobotMode mode) { onModeRequested(static_cast<int>(mode)); });
  connect(&panel_, &widgets::CommandPanel::moveDistanceRequested, controller_,
          &LinkController::moveDistance);
  connect(&panel_, &widgets::CommandPanel::turnAngleRequested, controller_,
          &LinkController::turnAngle);
  connect(health_panel_, &widgets::LinkHealthPanel::connectRequested, this,
          &LinkUi::chooseAndConnect);
  connect(health_panel_, &widgets::LinkHealthPanel::disconnectRequested, this,
          &LinkUi::backToSimulator);
  connect(controller_, &LinkController::linkedChanged, this, &LinkUi::onLinkedChanged);
  connect(controller_, &LinkController::healthChanged, this, &LinkUi::onHealthChanged);
}

LinkUi::~LinkUi() = default;

void LinkUi::setDialogRunner(DialogRunner runner) {
  if (runner)
    dialog_runner_ = std::move(runner);
}

widgets::SigningKeyTools LinkUi::signingKeyTools() {
  namespace mav = comms::mavlink;
  widgets::SigningKeyTools tools;
  tools.generate = [] {
    return QString::fromStdString(mav::signingKeyText(mav::randomSigningKey()));
  };
  tools.parse = [](const QString& text, QString* error) {
    const mav::SigningKeyResult key = mav::parseSigningKeyText(text.toStdString());
    if (!key.key) {
      if (error != nullptr)
        *error = QString::fromStdString(key.error);
      return QString();
    }
    return QString::fromStdString(mav::signingKeyText(*key.key));
  };
  tools.fingerprint = [](const QString& text) {
    const mav::SigningKeyResult key = mav::parseSigningKeyText(text.toStdString());
    return key.key ? QString::fromStdString(mav::signingKeyFingerprint(*key.key)) : QString();
  };
  return tools;
}

widgets::SigningChoice LinkUi::signingChoice() const {
  widgets::SigningChoice choice;
  choice.enabled = settings_.value(QString::fromLatin1(settings_key::kLinkSigning)).toBool();
  choice.key = settings_.value(QString::fromLatin1(settings_key::kLinkSigningKey)).toString();
  return choice;
}

void LinkUi::saveSigningChoice(const widgets::SigningChoice& choice) {
  settings_.setValue(QString::fromLatin1(settings_key::kLinkSigning), choice.enabled);
  if (choice.key.isEmpty()) {
    settings_.remove(QString::fromLatin1(settings_key::kLinkSigningKey));
    return;
  }
  settings_.setValue(QString::fromLatin1(settings_key::kLinkSigningKey), choice.key);
  if (!restrictSettingsToOwner(settings_))
    session_.report(EventLevel::kWarning,
                    tr("The settings file %1 holds the signing key but could not be made "
                       "readable by you only")
                        .arg(settings_.fileName()));
}

void LinkUi::applySigning() {
  const widgets::SigningChoice choice = signingChoice();
  std::optional<comms::mavlink::SigningKey> key;
  if (choice.enabled) {
    const auto parsed = comms::mavlink::parseSigningKeyText(choice.key.toStdString());
    if (!parsed.key)
      session_.report(EventLevel::kError,
                      tr("MAVLink signing is on but the saved key is unusable (%1): connecting "
                         "unsigned")
                          .arg(QString::fromStdString(parsed.error)));
    key = parsed.key;
  }
  controller_->setSigningKey(key);
}

void LinkUi::reportSigning(const QString& url) {
  const widgets::SigningChoice choice = signingChoice();
  if (!choice.enabled)
    return;
  const comms::LinkUrlResult parsed = comms::parseLinkUrl(url.trimmed().toStdString());
  if (parsed.url && comms::isArcosUrl(*parsed.url)) {
    session_.report(EventLevel::kWarning, tr("MAVLink signing does not apply to ARCOS: this "
                                             "link is not signed"));
    return;
  }
  session_.report(EventLevel::kInfo,
                  tr("MAVLink signing on, key %1: the robot needs the same key (irgs-robot "
                     "--signing-key)")
                      .arg(signingKeyTools().fingerprint(choice.key)));
}

QString LinkUi::connectTo(const QString& url) {
  applySigning();
  const QString problem = controller_->connectTo(url);
  if (!problem.isEmpty()) {
    session_.report(EventLevel::kError, tr("Cannot connect to %1: %2").arg(url, problem));
  } else {
    settings_.setValue(QString::fromLatin1(kLastLinkUrlKey), url.trimmed());
    reportSigning(url);
  }
  onLinkedChanged(controller_->linked());
  return problem;
}

bool LinkUi::chooseAndConnect() {
  widgets::ConnectionDialogOptions options;
  options.ports = LinkController::ports();
  options.rescan = &LinkController::ports;
  options.initial_url = controller_->linked()
                            ? controller_->url()
                            : settings_.value(QString::fromLatin1(kLastLinkUrlKey)).toString();
  options.validate = &validateLinkUrl;
  options.signing_tools = signingKeyTools();
  options.signing = signingChoice();
  options.save_signing = [this](const widgets::SigningChoice& choice) {
    saveSigningChoice(choice);
  };
  const std::optional<QString> url = dialog_runner_(std::move(options));
  if (!url) {
    onLinkedChanged(controller_->linked());  // the mode switch shows what is really in use
    return false;
  }
  return connectTo(*url).isEmpty();
}

void LinkUi::backToSimulator() {
  controller_->disconnectLink();
  onLinkedChanged(controller_->linked());
}

void LinkUi::onModeRequested(int mode) {
  if (static_cast<widgets::RobotMode>(mode) == widgets::RobotMode::kLinkedRobot)
    chooseAndConnect();
  else
    backToSimulator();
}

void LinkUi::onLinkedChanged(bool linked) {
  panel_.setMode(linked ? widgets::RobotMode::kLinkedRobot : widgets::RobotMode::kSimulator);
  // Firmware behaviour commands: a capability of the link (MAVLink's; ARCOS has none).
  panel_.setBehavioursVisible(linked && controller_->behaviourCommands() != nullptr);
  health_panel_->setVisible(linked);
  status_label_->setVisible(linked);
  if (linked)
    onHealthChanged(controller_->health());
}

void LinkUi::onHealthChanged(const widgets::LinkHealth& health) {
  health_panel_->setHealth(health);
  status_label_->setText(tr("link %1").arg(widgets::LinkHealthPanel::stateText(health.state)));
  status_label_->setStyleSheet(
      QStringLiteral("QLabel { color: %1; font-weight: bold; padding: 0 6px; }")
          .arg(widgets::LinkHealthPanel::stateColour(health.state)));
}

}  // namespace irgs::gui
