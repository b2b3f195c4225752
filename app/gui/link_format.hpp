#pragma once
// Conversions from the robot link's values (comms) to what the GUI shows: the link-health
// panel's struct, the port picker's entries, console levels and lines. The one place where the
// application translates comms vocabulary for the widgets, which never include comms.

#include <QString>
#include <cstdint>

#include "app/gui/session_controller.hpp"
#include "comms/link/link_types.hpp"
#include "comms/transport/port_discovery.hpp"
#include "widgets/link/connection_dialog.hpp"
#include "widgets/link/link_health_panel.hpp"

namespace irgs::gui {

widgets::LinkHealthState toHealthState(comms::LinkState state);
widgets::LinkHealth toLinkHealth(const comms::LinkStats& stats, const QString& link);
widgets::LinkPortEntry toPortEntry(const comms::SerialPortInfo& port);

// MAV_SEVERITY 0-3 (emergency, alert, critical, error) -> error; 4 (warning) -> warning;
// 5-7 (notice, info, debug) -> info.
EventLevel levelOfSeverity(std::uint8_t severity);
// The console line of a link event: "Robot: …" for STATUSTEXT, "Link: …" otherwise.
QString formatLinkEvent(const comms::LinkEvent& event);

// An empty string when `url` is a usable link URL, else the reason.
QString validateLinkUrl(const QString& url);

}  // namespace irgs::gui
