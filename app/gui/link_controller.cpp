#include "app/gui/link_controller.hpp"

#include <cmath>
#include <exception>
#include <stdexcept>

#include "app/gui/link_format.hpp"
#include "comms/link/link_url.hpp"
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

comms::MessageSamplerConfig guiMessageSampling() {
  comms::MessageSamplerConfig config;
  config.max_rate_hz = 25.0;
  return config;
}

comms::RemoteRobot* LinkController::remote() const {
  Robot* robot = session_.robot();
  return robot != nullptr ? robot->remoteRobot() : nullptr;
}

comms::FirmwareParameters* LinkController::firmwareParameters() const {
  comms::RemoteRobot* robot = remote();
  return robot != nullptr ? robot->firmwareParameters() : nullptr;
}

comms::MessageStream* LinkController::messageStream() const {
  comms::RemoteRobot* robot = remote();
  return robot != nullptr ? robot->messageStream() : nullptr;
}

comms::BehaviourCommands* LinkController::behaviourCommands() const {
  comms::RemoteRobot* robot = remote();
  return robot != nullptr ? robot->behaviourCommands() : nullptr;
}

QString LinkController::url() const {
  const comms::RemoteRobot* robot = remote();
  return robot != nullptr ? QString::fromStdString(robot->url()) : QString();
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
  RobotFactory factory =
      [io = io_, link_url = *parsed.url, tap = frame_tap_, signing = signing_key_](
          const WorldMap& world, const RobotProfile& profile) -> std::unique_ptr<Robot> {
    comms::RemoteRobotConfig config;
    config.mavlink.link.tap = tap;
    config.mavlink.link.signing_key = signing;
    config.mavlink.link.require_signed = signing.has_value();
    config.mavlink.messages = guiMessageSampling();
    // An ARCOS robot (docs/pioneer.md) counts from (0, 0, 0) at OPEN: it is taken to stand at
    // the map's start pose, so its sonar map lands on the map being shown.
    config.arcos.start_pose = world.start;
    comms::OpenRemoteRobotResult opened =
        comms::openRemoteRobot(io, link_url, profile, std::move(config));
    if (!opened.robot)
      throw std::runtime_error(opened.error);
    return std::move(opened.robot);
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
  const comms::RemoteRobot* robot = remote();
  if (robot == nullptr)
    return {};
  return toLinkHealth(robot->linkStats(), QString::fromStdString(robot->linkLabel()));
}

comms::TelemetryRates LinkController::rates() const {
  const comms::RemoteRobot* robot = remote();
  return robot != nullptr ? robot->telemetryRates() : comms::TelemetryRates{};
}

void LinkController::poll() {
  comms::RemoteRobot* robot = remote();
  if ((robot != nullptr) != was_linked_) {
    was_linked_ = robot != nullptr;
    emit linkedChanged(was_linked_);
  }
  if (robot == nullptr)
    return;
  // Link events, the robot's own texts (MAVLink STATUSTEXT; ARCOS: the handshake's robot name
  // and model, stalls), then the link state and byte counts.
  for (const comms::LinkEvent& event : robot->takeEvents())
    session_.report(levelOfSeverity(event.severity), formatLinkEvent(event));
  emit healthChanged(health());
}

bool LinkController::sendBehaviour(const comms::RobotBehaviourCommand& command,
                                   const QString& what) {
  comms::BehaviourCommands* commands = behaviourCommands();
  if (commands == nullptr)
    return false;
  // The result (accepted, rejected, timed out) arrives as a command-result link event.
  commands->sendBehaviour(command);
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
