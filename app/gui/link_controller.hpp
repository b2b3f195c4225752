#pragma once
// The robot link of the GUI: opens a linked robot (comms::LinkedRobot on one shared IoThread)
// and makes it the session's robot through the session's robot factory, goes back to the
// simulator, sends firmware behaviours, and polls the link on a timer: link events and the
// robot's STATUSTEXT go to the console (levels by severity), statistics to whoever shows them.

#include <QObject>
#include <QString>
#include <QTimer>
#include <memory>
#include <optional>
#include <vector>

#include "app/gui/linked_robot_handle.hpp"
#include "app/gui/session_controller.hpp"
#include "comms/link/frame_tap.hpp"
#include "comms/mavlink/signing.hpp"
#include "widgets/link/connection_dialog.hpp"
#include "widgets/link/link_health_panel.hpp"

namespace irgs::comms {
class ArcosRobot;
class IoThread;
}  // namespace irgs::comms

namespace irgs::gui {

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

  // A robot behind a link: MAVLink (handle()) or ARCOS (arcosRobot()).
  bool linked() const { return handle() != nullptr || arcosRobot() != nullptr; }
  QString url() const;
  // The session's robot when it is a linked one, else null.
  LinkedRobotHandle* handle() const;
  comms::ArcosRobot* arcosRobot() const;
  widgets::LinkHealth health() const;
  TelemetryRates rates() const;

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
  QString connected_url_;  // the URL of the last connectTo()
  bool was_linked_ = false;
};

}  // namespace irgs::gui
