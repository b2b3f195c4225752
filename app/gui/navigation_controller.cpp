#include "app/gui/navigation_controller.hpp"

#include <QStringList>
#include <QTabWidget>
#include <memory>

#include "app/gui/behaviour_controller.hpp"
#include "app/gui/session_controller.hpp"
#include "core/navigation/delivery_behaviour.hpp"
#include "core/navigation/ideal_ceiling_observer.hpp"
#include "widgets/canvas/map_canvas.hpp"
#include "widgets/navigation/navigation_panel.hpp"

namespace irgs::gui {

namespace {

QString routeText(const RoutePlan& route) {
  QStringList parts;
  for (const RouteStep& s : route.steps)
    parts << QStringLiteral("%1 (%2)").arg(QString::fromStdString(s.node_id),
                                           QString::fromLatin1(markerActionName(s.action)));
  return parts.join(QStringLiteral(" → ")) +
         QStringLiteral("\n%1 m").arg(route.length_m, 0, 'f', 1);
}

}  // namespace

NavigationController::NavigationController(SessionController& session, widgets::MapCanvas& canvas,
                                           QTabWidget& tabs, QObject* parent)
    : QObject(parent), session_(session), canvas_(canvas) {
  panel_ = new widgets::NavigationPanel(&tabs);
  tabs.addTab(panel_, tr("Navigate"));
  behaviours_ = new BehaviourController(session_, this);
  connect(panel_, &widgets::NavigationPanel::goRequested, this,
          [this](const QString& s, const QString& g) { go(s, g); });
  connect(panel_, &widgets::NavigationPanel::abortRequested, this, &NavigationController::abort);
  connect(behaviours_, &BehaviourController::finished, this,
          [this](bool failed, const QString& message) {
            panel_->setRunning(false);
            panel_->setState(failed ? tr("Failed: %1").arg(message) : tr("Arrived"));
          });
  connect(&session_, &SessionController::worldLoaded, this, &NavigationController::onWorldLoaded);
  connect(&session_, &SessionController::robotStateChanged, this,
          &NavigationController::refreshOverlay);
  onWorldLoaded();
}

NavigationController::~NavigationController() = default;

bool NavigationController::running() const {
  return behaviours_->running();
}

void NavigationController::onWorldLoaded() {
  if (behaviours_->running())
    behaviours_->abort(tr("a new map was loaded"));
  QStringList ids;
  for (const TopoNode& n : session_.worldMap().graph.nodes)
    ids << QString::fromStdString(n.id);
  panel_->setNodes(ids);
  route_.reset();
  delivery_ = nullptr;
  panel_->setRoute(ids.isEmpty() ? tr("This map has no topological graph") : tr("No route"));
  canvas_.setNavigationOverlay({});
}

bool NavigationController::go(const QString& start, const QString& goal) {
  const WorldMap& map = session_.worldMap();
  SimulatedWorld* world = session_.simulatedWorld();
  if (world == nullptr) {
    session_.report(EventLevel::kWarning,
                    tr("Navigate needs the simulator (the ceiling is seen by the ideal camera)"));
    return false;
  }
  RoutePlan route = planRoute(map.graph, start.toStdString(), goal.toStdString());
  if (route.status != RouteStatus::kOk) {
    session_.report(
        EventLevel::kWarning,
        tr("No route from node %1 to node %2: %3").arg(start, goal, routeStatusName(route.status)));
    return false;
  }
  auto observer = std::make_shared<IdealCeilingObserver>(map, IdealCameraParams{}, 1);
  auto behaviour = std::make_shared<DeliveryBehaviour>(route, session_.profile(), observer,
                                                       deliveryParamsFor(session_.profile()));
  // Shown first: a delivery that ends inside start() shows its end like any other.
  const std::shared_ptr<const DeliveryBehaviour> previous = std::exchange(delivery_, behaviour);
  std::optional<RoutePlan> previous_route = std::exchange(route_, route);
  panel_->setRoute(routeText(route));
  panel_->setRunning(true);
  if (!behaviours_->start(behaviour, tr("delivery %1 → %2").arg(start, goal))) {
    // Another activity drives the robot (the runner said so): nothing changes.
    delivery_ = previous;
    route_ = std::move(previous_route);
    panel_->setRunning(false);
    panel_->setRoute(route_ ? routeText(*route_) : tr("No route"));
    return false;
  }
  // The navigator keeps positions in the odometry frame, which is the map frame when the robot
  // starts on the start node: put it there, facing the map's start heading (before the next
  // robot update, so the delivery's first sample is taken there).
  const Vec2 at = route.steps.front().position;
  world->resetPose({at.x(), at.y(), map.start.theta});
  return true;
}

void NavigationController::abort() {
  behaviours_->abort(tr("aborted by the user"));
}

void NavigationController::refreshOverlay(const TelemetrySample& sample) {
  widgets::NavigationOverlay overlay;
  if (const SimulatedWorld* world = session_.simulatedWorld())
    overlay.moving_obstacles = world->movingObstaclePolygons();
  if (route_ && delivery_ && behaviours_->behaviour() == delivery_.get()) {
    for (const RouteStep& s : route_->steps)
      overlay.route.push_back(s.position);
    const LandmarkNavigator& nav = delivery_->navigator();
    overlay.next_node = nav.arrived() ? -1 : nav.nextStep();
    overlay.state = QString::fromLatin1(navStateName(nav.state()));
    overlay.robot = sample.true_pose.value_or(sample.odometry_pose);
    overlay.target = nav.lastOutput().target_body;
    overlay.repulsive = nav.lastOutput().repulsive_body;
    overlay.move = nav.lastOutput().move_body;
    if (overlay.state != last_state_) {
      last_state_ = overlay.state;
      panel_->setState(
          tr("%1 — next node %2")
              .arg(overlay.state)
              .arg(nav.arrived()
                       ? QStringLiteral("-")
                       : QString::fromStdString(
                             route_->steps[static_cast<std::size_t>(nav.nextStep())].node_id)));
    }
  }
  if (!overlay.empty() || !canvas_.navigationOverlay().empty())
    canvas_.setNavigationOverlay(std::move(overlay));
}

}  // namespace irgs::gui
