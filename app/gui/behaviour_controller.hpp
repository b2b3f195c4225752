#pragma once
// Runs one host-side Behaviour (core/behaviour/behaviour.hpp) against the session's robot,
// simulated or linked: every sample the robot produces goes to the behaviour, oldest first (the
// session's sample observer), and the behaviour's answer becomes the session's command schedule
// with the next change one robot step later, so the simulator applies it on the step after the
// sample at every simulation speed. Pausing stops the robot and hides the paused time from the
// behaviour (its clock continues where it stopped). A new robot (map loaded, reset) aborts it.

#include <QObject>
#include <QString>
#include <memory>

#include "core/behaviour/behaviour.hpp"
#include "core/robot/telemetry.hpp"

namespace irgs::gui {

class SessionController;

class BehaviourController : public QObject {
  Q_OBJECT

 public:
  explicit BehaviourController(SessionController& session, QObject* parent = nullptr);
  ~BehaviourController() override;

  // Replaces any running behaviour (the old one is aborted) and starts this one on the next
  // robot sample. `label` names it in the console ("goal", "coverage", "map building").
  void start(std::unique_ptr<Behaviour> behaviour, const QString& label);
  // Stops the robot and the behaviour; no-op when none runs. The behaviour object stays
  // available through behaviour() until the next start().
  void abort(const QString& reason);
  void setPaused(bool paused);

  bool running() const { return behaviour_ && !finished_; }
  bool paused() const { return paused_; }
  const QString& label() const { return label_; }
  // The current (or last finished) behaviour, or null.
  Behaviour* behaviour() { return behaviour_.get(); }
  const Behaviour* behaviour() const { return behaviour_.get(); }
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
  void onSample(const TelemetrySample& sample);
  void installHooks();
  void removeHooks();
  void finish(bool failed, const QString& message);

  SessionController& session_;
  std::unique_ptr<Behaviour> behaviour_;
  QString label_;
  VelocityCommand command_;
  double step_s_ = 0.01;         // robot step, learnt from the sample spacing
  double last_sample_s_ = -1.0;  // session time of the last sample seen
  double paused_total_s_ = 0.0;  // session time hidden from the behaviour while paused
  double paused_at_s_ = 0.0;
  bool paused_ = false;
  bool finished_ = false;
  std::string last_message_;
};

}  // namespace irgs::gui
