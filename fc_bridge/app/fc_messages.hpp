#pragma once

#include <cstdint>
#include <optional>

#include "cover/fc_bridge/agent_command.hpp"
#include "cover/fc_bridge/bridge.hpp"
#include "cover/msg/types.hpp"

namespace cover::fc_bridge {

// The bridge's plain types to and from the DDS messages.
AgentCommand from_msg(const msg::UavCommand& command);  // no allocation: the latency path
msg::FcState to_msg(const FcStatus& status, std::uint32_t uav_id, std::int64_t stamp_ns);
std::optional<OperatorCommand> from_msg(msg::FcCommandKind kind);
msg::FcCommandResult to_msg(CommandOutcome outcome);

// Whether two states differ in what a reader acts on (not the stamp, rates or counters).
bool differs(const msg::FcState& a, const msg::FcState& b);

}  // namespace cover::fc_bridge
