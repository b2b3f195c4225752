#pragma once
// A controller's handle on the host-side behaviours it runs (core/behaviour/behaviour.hpp) on
// the session's robot, simulated or linked. It does not drive the robot itself: it asks the
// session's ActivityRunner to run each behaviour as a BehaviourActivity, and reports, from the
// runner's signals, what happens to its own behaviours only (samples consumed, phase and
// progress, messages, the end). A start while another activity drives the robot is refused or
// preempts it, as the caller asks; a new robot (map loaded, reset) aborts it.

#include <QObject>
#include <QString>
#include <memory>

#include "app/gui/activity_runner.hpp"
#include "core/behaviour/behaviour.hpp"
#include "core/mission/mission.hpp"
#include "core/robot/telemetry.hpp"

namespace irgs::gui {

class SessionController;

class BehaviourController : public QObject {
  Q_OBJECT

 public:
  explicit BehaviourController(SessionController& session, QObject* parent = nullptr);
  // Stops its behaviour if it still runs (the runner must not outlive what it reports to).
  ~BehaviourController() override;

  // Asks the runner to start `behaviour` under `label` ("Goal", "Coverage", "Map building"); it
  // sees the robot's next sample. False when the runner refused it (a console line says why).
  bool start(std::shared_ptr<Behaviour> behaviour, const QString& label,
             ActivityRunner::Policy policy = ActivityRunner::Policy::kRefuseIfBusy);
  // The same for a host mission on motion primitives (map building, goal travel, coverage).
  bool start(std::shared_ptr<Mission> mission, const QString& label,
             ActivityRunner::Policy policy = ActivityRunner::Policy::kRefuseIfBusy);
  // Stops the robot and the behaviour; no-op when this controller's behaviour does not run. The
  // behaviour object stays available through behaviour() until the next start().
  void abort(const QString& reason);
  void setPaused(bool paused);

  bool running() const { return running_; }
  bool paused() const;
  const QString& label() const { return label_; }
  // The current (or last finished) behaviour or mission, or null (one of them is set).
  Behaviour* behaviour() { return behaviour_.get(); }
  const Behaviour* behaviour() const { return behaviour_.get(); }
  const Mission* mission() const { return mission_.get(); }
  BehaviourStatus status() const;

 signals:
  void started(const QString& label);
  // After every sample the behaviour consumed (phase and progress for the panel).
  void statusChanged(const irgs::BehaviourStatus& status);
  // A sample the behaviour consumed (session time), e.g. for coverage tracking.
  void sampleConsumed(const irgs::TelemetrySample& sample);
  // A new status().message (arrival at a turning point, loop closed, ...).
  void message(const QString& text);
  // Finished by itself (failed or not) or aborted (failed, reason as message).
  void finished(bool failed, const QString& message);

 private:
  bool launch(std::unique_ptr<Activity> activity, std::shared_ptr<Behaviour> behaviour,
              std::shared_ptr<Mission> mission, const QString& label,
              ActivityRunner::Policy policy);
  void onStarted(ActivityRunner::Id id);
  void onSampleConsumed(ActivityRunner::Id id, const TelemetrySample& sample);
  void onFinished(ActivityRunner::Id id, bool failed, const QString& message);

  ActivityRunner& runner_;
  std::shared_ptr<Behaviour> behaviour_;
  std::shared_ptr<Mission> mission_;
  QString label_;
  ActivityRunner::Id id_ = 0;  // of the last behaviour started here
  bool starting_ = false;      // inside start(): the runner's next started() is ours
  bool running_ = false;       // between the runner's started() and finished() for id_
  std::string last_message_;
};

}  // namespace irgs::gui
