#pragma once
// The linked robots irgs-sim can drive, behind one small interface: MAVLink (comms::LinkedRobot,
// irgs-robot and the IRGS firmware dialect) and ARCOS/P2OS (comms::ArcosRobot: Pioneers,
// MobileSim/AMRISim, `irgs-robot --protocol arcos`), chosen by the URL's protocol option. Both
// are an irgs::Robot; the adapter adds what a headless run reports about the link (state,
// statistics, console events, dropped samples) and a final stop that is confirmed:
//   MAVLink  zero MANUAL_CONTROL + IRGS_STOP, confirmed by its COMMAND_ACK (accepted);
//   ARCOS    STOP, confirmed when a later SIP reports both wheels at rest (|v| < 1 mm/s,
//            |omega| < 0.1 deg/s): ARCOS acknowledges no command, the SIP is its answer.
// Not thread-safe: one caller thread (the comms IoThread works underneath).

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "comms/link/link_types.hpp"
#include "comms/link/link_url.hpp"
#include "comms/mavlink/signing.hpp"
#include "comms/transport/io_thread.hpp"
#include "core/robot/robot.hpp"

namespace irgs::app {

class LinkAdapter {
 public:
  virtual ~LinkAdapter() = default;

  virtual Robot& robot() = 0;
  virtual std::string_view protocol() const = 0;  // "mavlink" or "arcos"
  virtual comms::LinkState linkState() const = 0;
  virtual comms::LinkStats linkStats() const = 0;
  virtual std::vector<comms::LinkEvent> takeEvents() = 0;
  virtual std::uint64_t droppedSamples() const = 0;

  // Drains the samples that arrived (robot().update(0)), oldest first; use this rather than
  // robot().update() so the stop confirmation sees them.
  virtual std::vector<TelemetrySample> update() = 0;
  // Sends the final stop (see the file comment). Idempotent.
  virtual void requestStop() = 0;
  // True once the stop was confirmed, false when the robot refused it, empty while waiting.
  virtual std::optional<bool> stopConfirmed() const = 0;
};

struct OpenLinkResult {
  std::unique_ptr<LinkAdapter> adapter;  // null when error is set
  std::string error;
};

// Opens the robot the URL names (it connects, and reconnects, on its own from then on). `io`
// must outlive the adapter. With `signing_key` the MAVLink link signs what it sends and accepts
// only frames signed with the key; an ARCOS URL with a key is an error (ARCOS has no signing).
OpenLinkResult openLinkAdapter(comms::IoThread& io, const comms::LinkUrl& url,
                               const RobotProfile& profile,
                               std::optional<comms::mavlink::SigningKey> signing_key = {});

}  // namespace irgs::app
