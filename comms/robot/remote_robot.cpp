#include "comms/robot/remote_robot.hpp"

#include <utility>

#include "comms/robot/arcos_remote_robot.hpp"
#include "comms/robot/mavlink_remote_robot.hpp"

namespace irgs::comms {

OpenRemoteRobotResult openRemoteRobot(std::shared_ptr<IoThread> io, const LinkUrl& url,
                                      const RobotProfile& profile, RemoteRobotConfig config) {
  OpenRemoteRobotResult out;
  const std::string name = config.name.empty() ? url.toString() : std::move(config.name);
  if (isArcosUrl(url)) {
    if (config.mavlink.link.signing_key) {
      out.error = "a signing key is MAVLink's: ARCOS has no signing";
      return out;
    }
    ArcosRobot::OpenResult opened =
        ArcosRobot::open(std::move(io), url, profile, std::move(config.arcos));
    if (opened.robot)
      out.robot = std::make_unique<ArcosRemoteRobot>(std::move(opened.robot), name);
    else
      out.error = std::move(opened.error);
    return out;
  }
  LinkedRobot::OpenResult opened = LinkedRobot::open(*io, url, profile, std::move(config.mavlink));
  if (opened.robot)
    out.robot = std::make_unique<MavlinkRemoteRobot>(std::move(io), std::move(opened.robot), name);
  else
    out.error = std::move(opened.error);
  return out;
}

OpenRemoteRobotResult openRemoteRobot(IoThread& io, const LinkUrl& url, const RobotProfile& profile,
                                      RemoteRobotConfig config) {
  // Not owned: the aliasing constructor with an empty owner keeps nothing alive.
  return openRemoteRobot(std::shared_ptr<IoThread>(std::shared_ptr<IoThread>(), &io), url, profile,
                         std::move(config));
}

}  // namespace irgs::comms
