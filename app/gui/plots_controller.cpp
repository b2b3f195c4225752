#include "app/gui/plots_controller.hpp"

#include <QAction>
#include <QDockWidget>
#include <QMainWindow>
#include <QMenu>
#include <QMenuBar>

#include "app/gui/link_controller.hpp"
#include "app/gui/localization_controller.hpp"
#include "app/gui/session_controller.hpp"
#include "comms/mavlink/field_info.hpp"
#include "comms/robot/message_sampler.hpp"
#include "widgets/link/link_health_panel.hpp"
#include "widgets/plots/plot_data_hub.hpp"
#include "widgets/plots/plots_dock.hpp"
#include "widgets/plots/telemetry_plot_fields.hpp"

namespace irgs::gui {

PlotsController::PlotsController(SessionController& session, LocalizationController& localization,
                                 LinkController& link, QMainWindow& window)
    : QObject(&window), session_(session), localization_(localization), link_(link) {
  hub_ = new widgets::PlotDataHub(widgets::PlotSeries::kDefaultCapacity, this);
  dock_ = new QDockWidget(tr("Plots"), &window);
  dock_->setObjectName(QStringLiteral("plotsDock"));
  plots_ = new widgets::PlotsDock(*hub_, dock_);
  dock_->setWidget(plots_);
  window.addDockWidget(Qt::BottomDockWidgetArea, dock_);
  dock_->hide();
  QAction* toggle = dock_->toggleViewAction();
  toggle->setText(tr("&Plots"));
  toggle->setShortcut(QKeySequence(Qt::CTRL | Qt::SHIFT | Qt::Key_P));
  if (auto* view = window.menuBar()->findChild<QMenu*>(QStringLiteral("viewMenu"))) {
    view->addSeparator();
    view->addAction(toggle);
  } else {
    window.addAction(toggle);
  }

  connect(&session_, &SessionController::robotStateChanged, this, &PlotsController::onSample);
  connect(&link, &LinkController::healthChanged, this, &PlotsController::onHealth);
  connect(&session_, &SessionController::ticked, this, &PlotsController::takeMessages);
}

QString PlotsController::mavlinkKey(const comms::MessageSample& message, std::size_t index) {
  const comms::mavlink::FieldInfo& field = message.message->fields[index];
  QString key =
      QStringLiteral("MAVLink/") + QLatin1String(message.message->name) + QLatin1Char('/');
  if (message.instance) {
    const auto instance = comms::mavlink::instanceField(*message.message);
    key += QLatin1String(message.message->fields[*instance].name) + QLatin1Char(' ') +
           QString::number(*message.instance) + QLatin1Char('/');
  }
  key += QLatin1String(field.name);
  if (field.array_index >= 0)
    key += QStringLiteral("[%1]").arg(field.array_index);
  return key;
}

void PlotsController::takeMessages() {
  comms::MessageStream* messages = link_.messageStream();
  if (messages == nullptr)
    return;
  // Message times are on the robot's sample clock; the session adds the same offset to samples.
  const double offset_s = session_.robotTimeOffset_s();
  for (const comms::MessageSample& message : messages->takeMessages()) {
    const std::uint64_t stream = (static_cast<std::uint64_t>(message.message->id) << 32) |
                                 message.instance.value_or(0xFFFFFFFFu);
    auto it = stream_keys_.find(stream);
    if (it == stream_keys_.end()) {
      StreamKeys keys;
      for (std::size_t i = 0; i < message.message->fields.size(); ++i) {
        keys.keys << mavlinkKey(message, i);
        keys.units << QString::fromUtf8(
            message.message->fields[i].unit.data(),
            static_cast<qsizetype>(message.message->fields[i].unit.size()));
      }
      it = stream_keys_.emplace(stream, std::move(keys)).first;
    }
    const double t = message.robot_time_s + offset_s;
    for (std::size_t i = 0; i < message.values.size(); ++i) {
      const auto k = static_cast<qsizetype>(i);
      hub_->record(it->second.keys[k], it->second.units[k], t, message.values[i], kMavlinkCapacity);
    }
  }
}

PlotsController::~PlotsController() = default;

void PlotsController::onSample(const TelemetrySample& sample) {
  hub_->record(sample.time_s, widgets::telemetryPlotFields(sample));
  const VelocityCommand& command = session_.command();
  hub_->record(QStringLiteral("Command/Velocity/linear"), QStringLiteral("m/s"), sample.time_s,
               command.linear_mps);
  hub_->record(QStringLiteral("Command/Velocity/angular"), QStringLiteral("rad/s"), sample.time_s,
               command.angular_radps);
  // The estimator has fed on this sample already (LocalizationController connects first).
  const EstimatorRunner* runner = localization_.runner();
  if (runner == nullptr)
    return;
  const EstimatorStep& step = runner->lastStep();
  if (runner != last_runner_ || step.index != last_estimator_index_) {
    last_runner_ = runner;
    last_estimator_index_ = step.index;
    hub_->record(sample.time_s, widgets::estimatorPlotFields(step));
  }
}

void PlotsController::onHealth(const widgets::LinkHealth& health) {
  if (health.state == widgets::LinkHealthState::kDisconnected)
    return;
  const double t = session_.displayTime_s();
  const QString g = QStringLiteral("Link/");
  hub_->record(
      t,
      {{g + QStringLiteral("Rates/rx bytes"), QStringLiteral("B/s"), health.rx_bytes_per_s},
       {g + QStringLiteral("Rates/tx bytes"), QStringLiteral("B/s"), health.tx_bytes_per_s},
       {g + QStringLiteral("Rates/rx messages"), QStringLiteral("msg/s"), health.rx_messages_per_s},
       {g + QStringLiteral("Rates/tx messages"), QStringLiteral("msg/s"), health.tx_messages_per_s},
       {g + QStringLiteral("Errors/CRC"), QStringLiteral("count"),
        static_cast<double>(health.crc_errors)},
       {g + QStringLiteral("Errors/sequence gaps"), QStringLiteral("count"),
        static_cast<double>(health.sequence_errors)},
       {g + QStringLiteral("Errors/other"), QStringLiteral("count"),
        static_cast<double>(health.other_errors)},
       {g + QStringLiteral("Quality/loss"), QStringLiteral("%"), health.loss_percent},
       {g + QStringLiteral("Quality/link losses"), QStringLiteral("count"),
        static_cast<double>(health.link_losses)}});
  if (health.rtt_s)
    hub_->record(g + QStringLiteral("Quality/round trip"), QStringLiteral("s"), t, *health.rtt_s);
  if (health.since_heartbeat_s)
    hub_->record(g + QStringLiteral("Quality/heartbeat age"), QStringLiteral("s"), t,
                 *health.since_heartbeat_s);
}

}  // namespace irgs::gui
