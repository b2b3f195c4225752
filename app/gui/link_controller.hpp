#pragma once
// The robot link of the GUI: opens a robot behind a link (comms::RemoteRobot, MAVLink or ARCOS,
// on one shared IoThread) and makes it the session's robot through the session's robot factory,
// goes back to the simulator, sends firmware behaviours, and polls the link on a timer: link
// events and the robot's own texts go to the console (levels by severity), statistics to
// whoever shows them. One code path for every protocol: what a protocol lacks is a null
// capability of the RemoteRobot.

#include <QObject>
#include <QString>
#include <QTimer>
#include <memory>
#include <optional>
#include <vector>

#include "app/gui/session_controller.hpp"
#include "comms/link/frame_tap.hpp"
#include "comms/mavlink/signing.hpp"
#include "comms/robot/remote_robot.hpp"
#include "widgets/link/connection_dialog.hpp"
#include "widgets/link/link_health_panel.hpp"

namespace irgs::gui {

// The decoded-message sampling the GUI's MAVLink robots ask for (LinkedRobotConfig::messages):
// every stream (message, or message instance) at up to 25 Hz — the full profile's 20 Hz
// streams whole, a replay at x16 thinned — for the plots' MAVLink fields.
comms::MessageSamplerConfig guiMessageSampling();

class LinkController : public QObject {
  Q_OBJECT

 public:
  static constexpr int kPollInterval_ms = 100;

  explicit LinkController(SessionController& session, QObject* parent = nullptr);
  ~LinkController() override;

  // Replaces the session's robot by a robot behind `url` (which reconnects on its own from now
  // on). Returns an empty string on success, else why not (bad URL or options); the session is
  // then unchanged.
  QString connectTo(const QString& url);
  // Back to the robot factory the session had before connecting (the simulator).
  void disconnectLink();
  // Links opened by later connectTo() calls report their bytes to `tap` (session recording);
  // an empty function: none.
  void setFrameTap(comms::FrameTap tap) { frame_tap_ = std::move(tap); }
  // MAVLink links opened by later connectTo() calls sign with `key` and accept only frames
  // signed with it; nothing: unsigned. ARCOS links are never signed.
  void setSigningKey(std::optional<comms::mavlink::SigningKey> key) { signing_key_ = key; }

  // The session's robot when it is behind a link (a live link or a replay), else null.
  comms::RemoteRobot* remote() const;
  bool linked() const { return remote() != nullptr; }
  QString url() const;
  widgets::LinkHealth health() const;
  comms::TelemetryRates rates() const;
  // The linked robot's optional capabilities; null when no robot is linked or it lacks one.
  comms::FirmwareParameters* firmwareParameters() const;
  comms::MessageStream* messageStream() const;
  comms::BehaviourCommands* behaviourCommands() const;

  // Firmware behaviours (acknowledged and retried by the link; the result reaches the console).
  // False when no robot is linked.
  bool moveDistance(double distance_m);
  bool turnAngle(double angle_rad);

  // The serial / Bluetooth ports of this computer for the connection dialog.
  static std::vector<widgets::LinkPortEntry> ports();

 public slots:
  void poll();  // also runs every kPollInterval_ms

 signals:
  void linkedChanged(bool linked);
  void healthChanged(const irgs::widgets::LinkHealth& health);

 private:
  bool sendBehaviour(const comms::RobotBehaviourCommand& command, const QString& what);

  SessionController& session_;
  std::shared_ptr<comms::IoThread> io_;  // created on the first connection
  RobotFactory simulator_factory_;
  comms::FrameTap frame_tap_;
  std::optional<comms::mavlink::SigningKey> signing_key_;
  QTimer poll_timer_;
  bool was_linked_ = false;
};

}  // namespace irgs::gui
