#include "comms/robot/arcos_robot.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <future>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <utility>

#include <boost/asio/post.hpp>
#include <boost/asio/steady_timer.hpp>

#include "comms/arcos/arcos_commands.hpp"
#include "comms/arcos/arcos_packet.hpp"
#include "comms/robot/arcos_motion.hpp"
#include "comms/robot/arcos_telemetry.hpp"
#include "comms/transport/transport_factory.hpp"

namespace irgs::comms {

namespace arc = arcos;

namespace {

bool positive(double v) {
  return std::isfinite(v) && v > 0.0;
}

LinkState linkStateOf(arc::ArcosState s, bool was_connected) {
  switch (s) {
    case arc::ArcosState::kDisconnected:
      return LinkState::kDisconnected;
    case arc::ArcosState::kSyncing:
    case arc::ArcosState::kOpening:
      return was_connected ? LinkState::kLost : LinkState::kConnecting;
    case arc::ArcosState::kConnected:
      return LinkState::kConnected;
    case arc::ArcosState::kLost:
      return LinkState::kLost;
  }
  return LinkState::kDisconnected;
}

}  // namespace

bool isArcosUrl(const LinkUrl& url) {
  const auto it = url.options.find("protocol");
  return it != url.options.end() && it->second == "arcos";
}

ArcosVelocityArguments arcosVelocityArguments(const VelocityCommand& command,
                                              const MotionLimits& limits) {
  if (!std::isfinite(command.linear_mps) || !std::isfinite(command.angular_radps))
    throw std::invalid_argument("arcosVelocityArguments: non-finite command");
  const double v = std::clamp(command.linear_mps, -limits.max_speed_mps, limits.max_speed_mps);
  const double w =
      std::clamp(command.angular_radps, -limits.max_turn_rate_radps, limits.max_turn_rate_radps);
  const double max = arc::kMaxIntArgument;
  return {static_cast<int>(std::clamp(std::round(v * 1000.0), -max, max)),
          static_cast<int>(std::clamp(std::round(radToDeg(w)), -max, max))};
}

namespace {

ArcosTelemetryConverter makeConverter(RobotProfile profile, ArcosParams params,
                                      const std::optional<Pose2>& start_pose) {
  ArcosTelemetryConverter converter(std::move(profile), std::move(params));
  if (start_pose)
    converter.setAnchor(*start_pose);
  return converter;
}

}  // namespace

struct ArcosRobot::Impl : std::enable_shared_from_this<ArcosRobot::Impl> {
  Impl(IoThread& io_thread, RobotProfile robot_profile, ArcosParams arcos_params,
       ArcosRobotConfig robot_config)
      : io(io_thread),
        config(robot_config),
        profile(robot_profile),
        session(robot_config.session),
        converter(makeConverter(std::move(robot_profile), std::move(arcos_params),
                                robot_config.start_pose)),
        timer(io_thread.context()),
        epoch(std::chrono::steady_clock::now()),
        backoff_s(robot_config.reconnect_initial_s) {}

  // ---- io thread only, except the members under `mutex` ----
  double now() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - epoch).count();
  }

  void start() {
    const double t = now();
    session.start(t);
    transport_state = TransportState::kOpening;
    transport->open();
    flush(t);
    arm();
  }

  void arm() {
    if (stopped)
      return;
    timer.expires_after(std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(config.tick_s)));
    timer.async_wait([self = shared_from_this()](const boost::system::error_code& ec) {
      if (ec || self->stopped)
        return;
      self->onTick();
      self->arm();
    });
  }

  void onTick() {
    const double t = now();
    if (transport_state == TransportState::kFailed && t >= reopen_at_s) {
      ++reconnect_attempts;
      pushEvent(LinkEventKind::kReconnecting, t, linkState(), 5,
                "reopening " + transport->description());
      transport_state = TransportState::kOpening;
      decoder.reset();
      transport->open();
    }
    session.tick(t);  // sends what the scheduler has due: changes, keep-alive
    flush(t);
  }

  // A drive() before the link was up goes out once it is (a loss clears the command first, so a
  // robot that comes back never resumes an old one).
  void resumeWanted(double t) {
    VelocityCommand wanted;
    {
      const std::lock_guard lock(mutex);
      wanted = command;
    }
    if (wanted != VelocityCommand{})
      wantVelocity(arcosVelocityArguments(wanted, profile.limits), t);
  }

  // A primitive's set points: speed, or a MOVE on a straight drive, and, far from the heading to
  // reach, that heading (HEAD) for the robot's own controller; near it a turn rate
  // (arcos_motion.hpp).
  void wantSetpoint(const ArcosMotionSetpoint& setpoint, double t) {
    if (session.state() != arc::ArcosState::kConnected)
      return;
    if (setpoint.move_mm) {
      session.commands().sendOnce(
          arc::commandPayload(arc::Command::kSetV, setpoint.move_speed_mmps));
      session.commands().want({arc::Command::kMove, *setpoint.move_mm});
    } else if (!setpoint.moving) {
      session.commands().want({arc::Command::kVel, setpoint.vel_mmps});
    }
    if (setpoint.head_deg)
      session.commands().want({arc::Command::kHead, *setpoint.head_deg});
    else
      session.commands().want({arc::Command::kRVel, setpoint.rvel_degps});
    session.pump(t);
  }

  // MotionControl calls, on the I/O thread: a primitive that ended between SIPs stops the
  // wheels at once.
  void afterMotionCall(double t) {
    if (primitives.takeStopOwed()) {
      session.sendUrgent(arc::Command::kStop);
      session.pump(t);
    }
    flush(t);
  }

  // The wanted set points; the scheduler sends them when they change (and as keep-alive).
  void wantVelocity(const ArcosVelocityArguments& a, double t) {
    if (session.state() != arc::ArcosState::kOpening &&
        session.state() != arc::ArcosState::kConnected)
      return;  // nothing to drive yet (the command is cleared on a link loss anyway)
    session.commands().want({arc::Command::kVel, a.vel_mmps});
    session.commands().want({arc::Command::kRVel, a.rvel_degps});
    session.pump(t);
  }

  void onBytes(std::span<const std::uint8_t> bytes) {
    const double t = now();
    rx_bytes += bytes.size();
    packets.clear();
    counters += decoder.feed(bytes, packets);
    for (const arc::Packet& p : packets)
      session.onPacket(p, t);
    flush(t);
  }

  void onTransportState(TransportState state, const std::string& message) {
    const double t = now();
    const TransportState before = transport_state;
    transport_state = state;
    if (!message.empty() && message != last_transport_message)
      pushEvent(LinkEventKind::kTransport, t, linkState(),
                static_cast<std::uint8_t>(state == TransportState::kFailed ? 4 : 6), message);
    last_transport_message = message;
    if (state == TransportState::kOpen) {
      backoff_s = config.reconnect_initial_s;
      decoder.reset();
      if (session.state() != arc::ArcosState::kConnected)
        session.start(t);  // synchronise from scratch on the new connection
    } else if (state == TransportState::kFailed && before != TransportState::kFailed) {
      reopen_at_s = t + backoff_s;
      backoff_s = std::min(config.reconnect_max_s, backoff_s * 2.0);
    }
    flush(t);
  }

  LinkState linkState() const { return linkStateOf(session.state(), was_connected); }

  void pushEvent(LinkEventKind kind, double t, LinkState state, int severity, std::string text) {
    LinkEvent e;
    e.kind = kind;
    e.time_s = t;
    e.state = state;
    e.severity = static_cast<std::uint8_t>(severity);
    e.text = std::move(text);
    const std::lock_guard lock(mutex);
    events.push_back(std::move(e));
    while (events.size() > config.max_pending_events)
      events.pop_front();
  }

  void sendOutgoing() {
    for (auto& packet : session.takeOutgoing()) {
      tx_bytes += packet.size();
      ++tx_packets;
      if (transport && transport_state == TransportState::kOpen)
        transport->send(packet);
    }
  }

  // Writes what the session queued and publishes its SIPs, events and state.
  void flush(double t) {
    sendOutgoing();
    const arc::ArcosState before = published_state;
    for (const arc::ArcosEvent& e : session.takeEvents()) {
      LinkEventKind kind = LinkEventKind::kTransport;
      if (e.state == arc::ArcosState::kSyncing)
        kind = was_connected ? LinkEventKind::kReconnecting : LinkEventKind::kConnecting;
      else if (e.state == arc::ArcosState::kConnected)
        kind = LinkEventKind::kLinkUp;
      else if (e.state == arc::ArcosState::kLost)
        kind = LinkEventKind::kLinkLost;
      else if (e.state == arc::ArcosState::kDisconnected)
        kind = LinkEventKind::kClosed;
      if (e.state == arc::ArcosState::kConnected && !was_connected)
        was_connected = true;
      pushEvent(kind, e.time_s, linkStateOf(e.state, was_connected),
                static_cast<std::uint8_t>(e.warning ? 4 : 6), e.text);
    }
    const arc::ArcosState state = session.state();
    if (state != before) {
      if (before == arc::ArcosState::kConnected) {
        ++link_losses;
        bool cleared = false;
        {
          const std::lock_guard lock(mutex);
          cleared = command != VelocityCommand{};
          command = {};
        }
        if (cleared)
          pushEvent(LinkEventKind::kLinkLost, t, linkState(), 4,
                    "ARCOS: link lost while driving; the command is cleared (drive again)");
      }
      if (before == arc::ArcosState::kConnected)
        primitives.abort(motion::Reason::kSafety);  // its set points went with the link
      if (state == arc::ArcosState::kOpening)
        converter.reset();  // a new connection: the robot may have restarted its odometry
      if (state == arc::ArcosState::kConnected)
        resumeWanted(t);
      published_state = state;
    }
    std::vector<arc::StandardSip> sips = session.takeSips();
    bool stalled_now = false;
    std::vector<TelemetrySample> converted;
    converted.reserve(sips.size());
    for (const arc::StandardSip& sip : sips) {
      converted.push_back(converter.convert(sip, t));
      stalled_now = sip.leftStalled() || sip.rightStalled();
      if (const auto setpoint =
              primitives.onSample(converted.back(), converter.mapToOdometryHeading_rad()))
        wantSetpoint(*setpoint, t);
    }
    sendOutgoing();  // the set points of these SIPs go out now, not on the next tick
    if (!sips.empty() && stalled_now != stalled) {
      stalled = stalled_now;
      pushEvent(LinkEventKind::kStatusText, t, linkState(),
                static_cast<std::uint8_t>(stalled ? 4 : 6),
                stalled ? "ARCOS: wheels stalled" : "ARCOS: wheels free again");
    }
    const std::lock_guard lock(mutex);
    for (motion::MotionReport& r : primitives.takeReports())
      reports.push_back(r);
    while (reports.size() > ArcosMotion::kMaxKeptReports)
      reports.pop_front();
    for (auto& s : converted) {
      noteArrival(s, t);
      samples.push_back(std::move(s));
      if (samples.size() > config.max_pending_samples) {
        samples.pop_front();
        ++dropped_samples;
      }
    }
    state_snapshot = state;
    identity_snapshot = session.identity();
    session_stats = session.stats();
    stats_snapshot.state = linkState();
    stats_snapshot.rx_bytes = rx_bytes;
    stats_snapshot.tx_bytes = tx_bytes;
    stats_snapshot.rx_messages = counters.packets;
    stats_snapshot.tx_messages = tx_packets;
    stats_snapshot.crc_errors = counters.bad_checksum;
    stats_snapshot.other_errors = counters.bad_count + session_stats.bad_sips;
    stats_snapshot.link_losses = link_losses;
    stats_snapshot.reconnect_attempts = reconnect_attempts;
    if (session_stats.last_sip_s)
      stats_snapshot.since_heartbeat_s = t - *session_stats.last_sip_s;
    updateRates(t);
  }

  // Sliding-window byte and packet rates for the link-health panel, as the MAVLink session
  // reports them (caller holds `mutex`).
  void updateRates(double t) {
    totals.push_back({t, rx_bytes, tx_bytes, counters.packets, tx_packets});
    while (totals.size() > 2 && t - totals.front().t > kRateWindow_s)
      totals.pop_front();
    const Totals& first = totals.front();
    const double span = t - first.t;
    if (span <= 0.0)
      return;
    stats_snapshot.rx_bytes_per_s = static_cast<double>(rx_bytes - first.rx_bytes) / span;
    stats_snapshot.tx_bytes_per_s = static_cast<double>(tx_bytes - first.tx_bytes) / span;
    stats_snapshot.rx_messages_per_s = static_cast<double>(counters.packets - first.rx) / span;
    stats_snapshot.tx_messages_per_s = static_cast<double>(tx_packets - first.tx) / span;
    stats_snapshot.tx_budget_bytes_per_s = config.session.commands.baud / 10.0;
  }

  // Rate bookkeeping (caller holds `mutex`): arrival time and sonar count of every sample,
  // kept for ArcosTelemetryRates::kWindow_s.
  void noteArrival(const TelemetrySample& sample, double t) {
    ++total_samples;
    total_sonar_readings += sample.sonar.size();
    arrivals.push_back({t, sample.sonar.size()});
    while (!arrivals.empty() && arrivals.front().first < t - ArcosTelemetryRates::kWindow_s)
      arrivals.pop_front();
  }

  void shutdownNow() {
    if (stopped)
      return;
    // CLOSE: a robot left open would keep streaming to nobody. It is one more command packet:
    // keep the scheduler's gap to the last one (<= 20 ms) so that the robot does not drop it.
    const double gap_s = session.commands().gapLeft(now());
    if (gap_s > 0.0)
      std::this_thread::sleep_for(std::chrono::duration<double>(gap_s));
    const double t = now();
    session.stop(t);
    for (auto& packet : session.takeOutgoing()) {
      if (transport && transport_state == TransportState::kOpen)
        transport->send(packet);
    }
    stopped = true;
    timer.cancel();
    transport.reset();  // no transport callback after this
  }

  IoThread& io;
  ArcosRobotConfig config;
  RobotProfile profile;
  arc::ArcosClientSession session;
  ArcosTelemetryConverter converter;
  ArcosMotion primitives{profile};
  boost::asio::steady_timer timer;
  std::chrono::steady_clock::time_point epoch;
  std::unique_ptr<Transport> transport;
  arc::PacketDecoder decoder;
  std::vector<arc::Packet> packets;
  arc::PacketCounters counters;
  TransportState transport_state = TransportState::kClosed;
  std::string last_transport_message;
  double reopen_at_s = 0.0;
  double backoff_s;
  bool stopped = false;
  bool was_connected = false;
  bool stalled = false;
  arc::ArcosState published_state = arc::ArcosState::kDisconnected;
  std::uint64_t rx_bytes = 0;
  std::uint64_t tx_bytes = 0;
  std::uint64_t tx_packets = 0;
  struct Totals {
    double t;
    std::uint64_t rx_bytes, tx_bytes, rx, tx;
  };
  static constexpr double kRateWindow_s = 2.0;
  std::deque<Totals> totals;  // for the rates over the last kRateWindow_s
  std::uint32_t link_losses = 0;
  std::uint32_t reconnect_attempts = 0;

  // Shared with the caller's thread.
  mutable std::mutex mutex;
  VelocityCommand command;
  std::deque<TelemetrySample> samples;
  std::deque<motion::MotionReport> reports;
  double handed_out_s = 0.0;  // time of the newest sample update() returned
  std::deque<LinkEvent> events;
  std::uint64_t dropped_samples = 0;
  std::uint64_t total_samples = 0;
  std::uint64_t total_sonar_readings = 0;
  std::deque<std::pair<double, std::size_t>> arrivals;  // (arrival s, sonar readings)
  arc::ArcosState state_snapshot = arc::ArcosState::kDisconnected;
  std::optional<arc::RobotIdentity> identity_snapshot;
  arc::ArcosStats session_stats;
  LinkStats stats_snapshot;
};

ArcosRobot::OpenResult ArcosRobot::open(IoThread& io, const LinkUrl& url, RobotProfile profile,
                                        ArcosRobotConfig config) {
  if (!positive(config.tick_s) || !positive(config.reconnect_initial_s) ||
      config.reconnect_max_s < config.reconnect_initial_s)
    return {nullptr, "arcos config: tick and reconnect delays must be > 0"};
  // The command budget follows the link: the URL's baud, else the configured one (the
  // Pioneer's default HostBaud, 9600: a TCP link to a real robot ends in its serial port).
  if (const auto baud = linkBaud(url))
    config.session.commands.baud = *baud;
  ArcosParamsResult params = arcosParamsFromProfile(profile);
  std::shared_ptr<Impl> impl;
  try {
    impl = std::make_shared<Impl>(io, profile, params.params, config);
  } catch (const std::invalid_argument& e) {
    return {nullptr, std::string("arcos config: ") + e.what()};
  }
  for (const std::string& w : params.warnings)
    impl->pushEvent(LinkEventKind::kTransport, 0.0, LinkState::kDisconnected, 4, w);
  if (!params.found)
    impl->pushEvent(
        LinkEventKind::kTransport, 0.0, LinkState::kDisconnected, 5,
        "profile " + profile.name + " has no `arcos` conversion factors; using the P3-DX values");
  TransportCallbacks tc;
  Impl* raw = impl.get();  // Impl destroys the transport (no callback after) before it dies
  tc.on_bytes = [raw](std::span<const std::uint8_t> bytes) { raw->onBytes(bytes); };
  tc.on_state = [raw](TransportState state, const std::string& message) {
    raw->onTransportState(state, message);
  };
  TransportResult made = makeTransport(url, io, std::move(tc));
  if (!made.transport)
    return {nullptr, made.error};
  impl->transport = std::move(made.transport);
  boost::asio::post(io.context(), [impl] { impl->start(); });
  return {std::unique_ptr<ArcosRobot>(
              new ArcosRobot(std::move(profile), url.toString(), params.params, impl)),
          {}};
}

ArcosRobot::OpenResult ArcosRobot::open(std::shared_ptr<IoThread> io, const LinkUrl& url,
                                        RobotProfile profile, ArcosRobotConfig config) {
  if (!io)
    throw std::invalid_argument("ArcosRobot::open: null IoThread");
  OpenResult result = open(*io, url, std::move(profile), std::move(config));
  if (result.robot)
    result.robot->io_keepalive_ = std::move(io);
  return result;
}

ArcosRobot::ArcosRobot(RobotProfile profile, std::string url_text, ArcosParams params,
                       std::shared_ptr<Impl> impl)
    : profile_(std::move(profile)),
      url_text_(std::move(url_text)),
      params_(std::move(params)),
      impl_(std::move(impl)) {}

ArcosRobot::~ArcosRobot() {
  IoThread& io = impl_->io;
  if (io.isCurrentThread() || !io.running()) {
    impl_->shutdownNow();
    return;
  }
  std::promise<void> done;
  boost::asio::post(io.context(), [&done, impl = impl_] {
    impl->shutdownNow();
    done.set_value();
  });
  done.get_future().wait();
}

const RobotProfile& ArcosRobot::profile() const {
  return profile_;
}

std::string ArcosRobot::describe() const {
  const std::lock_guard lock(impl_->mutex);
  std::string text = url_text_ + " (" + arc::toString(impl_->state_snapshot);
  if (impl_->identity_snapshot)
    text += ": " + impl_->identity_snapshot->name + " " + impl_->identity_snapshot->robot_class +
            " " + impl_->identity_snapshot->subclass;
  return text + ")";
}

void ArcosRobot::drive(const VelocityCommand& command) {
  // Throws for a non-finite command before anything changes.
  const ArcosVelocityArguments arguments = arcosVelocityArguments(command, profile_.limits);
  {
    const std::lock_guard lock(impl_->mutex);
    impl_->command = command;
  }
  boost::asio::post(impl_->io.context(), [impl = impl_, arguments] {
    if (impl->stopped)
      return;
    const double t = impl->now();
    impl->primitives.cancel();  // teleop takes over from a running primitive
    impl->primitives.takeStopOwed();
    impl->wantVelocity(arguments, t);  // sent now if the scheduler allows, else on a tick
    impl->flush(t);
  });
}

void ArcosRobot::stop() {
  {
    const std::lock_guard lock(impl_->mutex);
    impl_->command = {};
  }
  boost::asio::post(impl_->io.context(), [impl = impl_] {
    if (impl->stopped)
      return;
    const double t = impl->now();
    impl->primitives.cancel();
    impl->primitives.takeStopOwed();                // the STOP below is the stop
    impl->session.sendUrgent(arc::Command::kStop);  // ahead of any set point still waiting
    impl->session.pump(t);
    impl->flush(t);
  });
}

std::vector<TelemetrySample> ArcosRobot::update(double /*wall_elapsed_s*/) {
  const std::lock_guard lock(impl_->mutex);
  std::vector<TelemetrySample> out(std::make_move_iterator(impl_->samples.begin()),
                                   std::make_move_iterator(impl_->samples.end()));
  impl_->samples.clear();
  if (!out.empty())
    impl_->handed_out_s = out.back().time_s;
  return out;
}

bool ArcosRobot::supports(motion::PrimitiveKind kind) const {
  return impl_->primitives.supports(kind);  // constant: no I/O-thread state involved
}

void ArcosRobot::start(const motion::Primitive& primitive) {
  boost::asio::post(impl_->io.context(), [impl = impl_, primitive] {
    if (impl->stopped)
      return;
    impl->primitives.start(primitive);
    impl->afterMotionCall(impl->now());
  });
}

void ArcosRobot::cancel() {
  boost::asio::post(impl_->io.context(), [impl = impl_] {
    if (impl->stopped)
      return;
    impl->primitives.cancel();
    impl->afterMotionCall(impl->now());
  });
}

std::vector<motion::MotionReport> ArcosRobot::takeReports() {
  // Only reports up to the newest sample handed out: the caller sees the samples first.
  const std::lock_guard lock(impl_->mutex);
  std::vector<motion::MotionReport> out;
  while (!impl_->reports.empty() && impl_->reports.front().time_s <= impl_->handed_out_s) {
    out.push_back(impl_->reports.front());
    impl_->reports.pop_front();
  }
  return out;
}

LinkState ArcosRobot::linkState() const {
  const std::lock_guard lock(impl_->mutex);
  return impl_->stats_snapshot.state;
}

LinkStats ArcosRobot::linkStats() const {
  const std::lock_guard lock(impl_->mutex);
  return impl_->stats_snapshot;
}

std::vector<LinkEvent> ArcosRobot::takeEvents() {
  const std::lock_guard lock(impl_->mutex);
  std::vector<LinkEvent> out(impl_->events.begin(), impl_->events.end());
  impl_->events.clear();
  return out;
}

arcos::ArcosState ArcosRobot::sessionState() const {
  const std::lock_guard lock(impl_->mutex);
  return impl_->state_snapshot;
}

std::optional<arcos::RobotIdentity> ArcosRobot::identity() const {
  const std::lock_guard lock(impl_->mutex);
  return impl_->identity_snapshot;
}

std::uint64_t ArcosRobot::droppedSamples() const {
  const std::lock_guard lock(impl_->mutex);
  return impl_->dropped_samples;
}

ArcosTelemetryRates ArcosRobot::telemetryRates() const {
  const std::lock_guard lock(impl_->mutex);
  ArcosTelemetryRates rates;
  rates.samples = impl_->total_samples;
  rates.sonar_readings = impl_->total_sonar_readings;
  // Only arrivals within the window of now count (a silent link reads 0 Hz). Several SIPs can
  // arrive in one read: the rate is taken over the window's span, the first arrival opening it
  // (as LinkedRobotHandle does on the robot's clock).
  const double oldest_s = impl_->now() - ArcosTelemetryRates::kWindow_s;
  std::vector<std::pair<double, std::size_t>> recent;
  for (const auto& arrival : impl_->arrivals) {
    if (arrival.first >= oldest_s)
      recent.push_back(arrival);
  }
  if (recent.size() < 2)
    return rates;
  const double span_s = recent.back().first - recent.front().first;
  if (!(span_s > 0.0))
    return rates;
  std::size_t with_sonar = 0;
  std::size_t readings = 0;
  for (std::size_t i = 1; i < recent.size(); ++i) {
    with_sonar += recent[i].second > 0 ? 1 : 0;
    readings += recent[i].second;
  }
  rates.sample_hz = static_cast<double>(recent.size() - 1) / span_s;
  rates.sonar_hz = static_cast<double>(with_sonar) / span_s;
  rates.sonar_readings_per_s = static_cast<double>(readings) / span_s;
  return rates;
}

}  // namespace irgs::comms
