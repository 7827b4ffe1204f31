#include "cover/dds/qos.hpp"

#include <cmath>

#include "cover/dds/dds_error.hpp"

namespace cover::dds {

void QosProfile::validate() const {
  if (history_depth < 1 || history_depth > 1000) {
    throw DdsError("QoS profile '" + name + "': history_depth must be in 1..1000");
  }
  if (max_instances < 1 || max_instances > 100000) {
    throw DdsError("QoS profile '" + name + "': max_instances must be in 1..100000");
  }
  if (!std::isfinite(deadline_s) || deadline_s < 0) {
    throw DdsError("QoS profile '" + name + "': deadline_s must be >= 0");
  }
  if (!std::isfinite(acknowledgement_delay_s) || acknowledgement_delay_s < 0 ||
      acknowledgement_delay_s > 1.0) {
    throw DdsError("QoS profile '" + name + "': acknowledgement_delay_s must be in 0..1");
  }
}

QosProfile sensor_qos() {
  return {"sensor", Reliability::BestEffort, Durability::Volatile, 1, 0.05};
}

QosProfile command_qos() {
  return {"command", Reliability::Reliable, Durability::Volatile, 1, 0.05};
}

QosProfile state_qos() {
  return {"state", Reliability::Reliable, Durability::TransientLocal, 8, 0.0};
}

QosProfile request_qos() {
  return {"request", Reliability::Reliable, Durability::Volatile, 64, 0.0};
}

QosProfile exchange_qos() {
  return {"exchange", Reliability::BestEffort, Durability::Volatile, 64, 0.0};
}

std::vector<std::string> qos_profile_names() {
  return {"sensor", "command", "state", "request", "exchange"};
}

QosProfile qos_profile(std::string_view name) {
  if (name == "sensor") return sensor_qos();
  if (name == "command") return command_qos();
  if (name == "state") return state_qos();
  if (name == "request") return request_qos();
  if (name == "exchange") return exchange_qos();
  throw DdsError("unknown QoS profile '" + std::string(name) +
                 "' (expected sensor, command, state, request or exchange)");
}

}  // namespace cover::dds
