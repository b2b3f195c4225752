#include "app/gui/link_controller.hpp"

#include <cmath>
#include <exception>
#include <stdexcept>

#include "app/gui/link_format.hpp"
#include "comms/link/link_url.hpp"
#include "comms/robot/arcos_robot.hpp"
#include "comms/transport/io_thread.hpp"
#include "comms/transport/port_discovery.hpp"

namespace irgs::gui {

LinkController::LinkController(SessionController& session, QObject* parent)
    : QObject(parent), session_(session) {
  poll_timer_.setInterval(kPollInterval_ms);
  connect(&poll_timer_, &QTimer::timeout, this, &LinkController::poll);
  poll_timer_.start();
}

LinkController::~LinkController() = default;

LinkedRobotHandle* LinkController::handle() const {
  return dynamic_cast<LinkedRobotHandle*>(session_.robot());
}

comms::ArcosRobot* LinkController::arcosRobot() const {
  return dynamic_cast<comms::ArcosRobot*>(session_.robot());
}

QString LinkController::url() const {
  if (const LinkedRobotHandle* linked = handle())
    return QString::fromStdString(linked->url());
  return arcosRobot() != nullptr ? connected_url_ : QString();
}

QString LinkController::connectTo(const QString& url) {
  const comms::LinkUrlResult parsed = comms::parseLinkUrl(url.trimmed().toStdString());
  if (!parsed.url)
    return QString::fromStdString(parsed.error);
  if (!io_)
    io_ = std::make_shared<comms::IoThread>();
  if (!linked())
    simulator_factory_ = session_.robotFactory();
  const std::string text = parsed.url->toString();
  connected_url_ = QString::fromStdString(text);
  RobotFactory factory =
      [io = io_, link_url = *parsed.url, text, tap = frame_tap_, signing = signing_key_](
          const WorldMap& world, const RobotProfile& profile) -> std::unique_ptr<Robot> {
    if (comms::isArcosUrl(link_url)) {
      // A Pioneer over ARCOS (docs/pioneer.md): a plain Robot that keeps the io thread alive.
      // ARCOS counts from (0, 0, 0) at OPEN: the robot is taken to stand at the map's start
      // pose, so its sonar map lands on the map being shown.
      comms::ArcosRobotConfig config;
      config.start_pose = world.start;
      comms::ArcosRobot::OpenResult arcos = comms::ArcosRobot::open(io, link_url, profile, config);
      if (!arcos.robot)
        throw std::runtime_error(arcos.error);
      return std::unique_ptr<Robot>(std::move(arcos.robot));
    }
    comms::LinkedRobotConfig config;
    config.link.tap = tap;
    config.link.signing_key = signing;
    config.link.require_signed = signing.has_value();
    config.messages = guiMessageSampling();
    comms::LinkedRobot::OpenResult opened =
        comms::LinkedRobot::open(*io, link_url, profile, std::move(config));
    if (!opened.robot)
      throw std::runtime_error(opened.error);
    return std::make_unique<LinkedRobotHandle>(io, std::move(opened.robot), text);
  };
  try {
    session_.setRobotFactory(std::move(factory));
  } catch (const std::exception& e) {
    return QString::fromUtf8(e.what());
  }
  session_.resetGrid();  // the simulator's map of the room is not the robot's
  session_.report(EventLevel::kInfo,
                  tr("Connecting to the robot at %1").arg(QString::fromStdString(text)));
  poll();
  return {};
}

void LinkController::disconnectLink() {
  if (!linked())
    return;
  session_.stopRobot();
  if (simulator_factory_) {
    session_.setRobotFactory(simulator_factory_);
    session_.resetGrid();
    session_.report(EventLevel::kInfo, tr("Link closed; back to the simulator"));
  }
  poll();
}

widgets::LinkHealth LinkController::health() const {
  if (const comms::ArcosRobot* arcos = arcosRobot())
    return toLinkHealth(arcos->linkStats(), QString::fromStdString(arcos->describe()));
  LinkedRobotHandle* linked = handle();
  if (linked == nullptr)
    return {};
  return toLinkHealth(linked->linked().linkStats(), QString::fromStdString(linked->url()));
}

TelemetryRates LinkController::rates() const {
  if (const comms::ArcosRobot* arcos = arcosRobot()) {
    const comms::ArcosTelemetryRates r = arcos->telemetryRates();
    TelemetryRates rates;
    rates.samples = r.samples;
    rates.sonar_readings = r.sonar_readings;
    rates.odometry_hz = r.sample_hz;
    rates.sonar_hz = r.sonar_hz;
    rates.sonar_readings_per_s = r.sonar_readings_per_s;
    return rates;
  }
  const LinkedRobotHandle* linked = handle();
  return linked != nullptr ? linked->rates() : TelemetryRates{};
}

void LinkController::poll() {
  LinkedRobotHandle* linked = handle();
  if (this->linked() != was_linked_) {
    was_linked_ = this->linked();
    emit linkedChanged(was_linked_);
  }
  // An ARCOS robot's events (the handshake's robot name and model, link loss, stalls) and its
  // link state and byte counts, as for MAVLink.
  if (auto* arcos = arcosRobot()) {
    for (const comms::LinkEvent& event : arcos->takeEvents())
      session_.report(levelOfSeverity(event.severity), formatLinkEvent(event));
    emit healthChanged(health());
  }
  if (linked == nullptr)
    return;
  for (const comms::LinkEvent& event : linked->linked().takeEvents())
    session_.report(levelOfSeverity(event.severity), formatLinkEvent(event));
  emit healthChanged(health());
}

bool LinkController::sendBehaviour(const comms::RobotBehaviourCommand& command,
                                   const QString& what) {
  LinkedRobotHandle* linked = handle();
  if (linked == nullptr)
    return false;
  // The result (accepted, rejected, timed out) arrives as a command-result link event.
  linked->linked().sendBehaviour(command);
  session_.report(EventLevel::kInfo, tr("Behaviour: %1").arg(what));
  return true;
}

bool LinkController::moveDistance(double distance_m) {
  if (!std::isfinite(distance_m))
    return false;
  comms::RobotBehaviourCommand command;
  command.kind = comms::RobotBehaviourKind::kMoveDistance;
  command.distance_m = distance_m;
  return sendBehaviour(command, tr("move %1 m").arg(distance_m, 0, 'f', 2));
}

bool LinkController::turnAngle(double angle_rad) {
  if (!std::isfinite(angle_rad))
    return false;
  comms::RobotBehaviourCommand command;
  command.kind = comms::RobotBehaviourKind::kTurnAngle;
  command.angle_rad = angle_rad;
  return sendBehaviour(command, tr("turn %1°").arg(radToDeg(angle_rad), 0, 'f', 0));
}

std::vector<widgets::LinkPortEntry> LinkController::ports() {
  std::vector<widgets::LinkPortEntry> entries;
  for (const comms::SerialPortInfo& port : comms::discoverSerialPorts())
    entries.push_back(toPortEntry(port));
  return entries;
}

}  // namespace irgs::gui
