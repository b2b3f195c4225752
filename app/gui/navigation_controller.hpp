#pragma once
// Landmark navigation in the GUI (issue 7, paper 002): the "Navigate" tab (start and goal node,
// Go, Abort, route and state) and the navigation overlay on the map canvas (route over the
// topological graph, the navigator's state, the repulsive, target and move vectors on the robot,
// the simulator's moving obstacles). Go asks the session's runner to run a DeliveryBehaviour
// (through its own BehaviourController: refused while another activity drives the robot) and
// teleports the simulated robot onto the start node; the ceiling is seen by the ideal geometric
// observer (core/navigation), so this works without the camera dock.
//
// Simulator mode only: the ideal observer projects the map at the robot's true pose.

#include <QObject>
#include <QString>
#include <memory>
#include <optional>

#include "core/navigation/route_plan.hpp"
#include "core/robot/telemetry.hpp"

class QTabWidget;

namespace irgs {
class DeliveryBehaviour;
}
namespace irgs::widgets {
class MapCanvas;
class NavigationPanel;
}  // namespace irgs::widgets

namespace irgs::gui {

class BehaviourController;
class SessionController;

class NavigationController : public QObject {
  Q_OBJECT

 public:
  // Adds the "Navigate" tab to `tabs`. Everything must outlive the controller.
  NavigationController(SessionController& session, widgets::MapCanvas& canvas, QTabWidget& tabs,
                       QObject* parent = nullptr);
  ~NavigationController() override;

  // Plans and starts a delivery; false (with a console message) when it cannot.
  bool go(const QString& start, const QString& goal);
  void abort();

  bool running() const;
  const DeliveryBehaviour* delivery() const { return delivery_.get(); }
  widgets::NavigationPanel& panel() const { return *panel_; }
  BehaviourController& behaviours() const { return *behaviours_; }

 private:
  void onWorldLoaded();
  void refreshOverlay(const TelemetrySample& sample);

  SessionController& session_;
  widgets::MapCanvas& canvas_;
  widgets::NavigationPanel* panel_ = nullptr;
  BehaviourController* behaviours_ = nullptr;
  std::shared_ptr<const DeliveryBehaviour> delivery_;  // the last one started here
  std::optional<RoutePlan> route_;
  QString last_state_;
};

}  // namespace irgs::gui
