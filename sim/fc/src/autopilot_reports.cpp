// The simulated autopilot's state changes, and how each firmware tells its companion about
// them: ArduPilot in STATUSTEXT (only on a link that has received a frame), PX4 in EVENTs
// (never STATUSTEXT). cover-sim's log and the run's result get every one (events()).
#include <algorithm>
#include <cmath>

#include "cover/sim/fc/simulated_autopilot.hpp"

namespace cover::sim::fc {

namespace {

constexpr std::uint8_t kSeverityInfo = 6;

std::uint32_t boot_ms(double now_s) {
  return static_cast<std::uint32_t>(std::llround(std::max(0.0, now_s) * 1000.0));
}

}  // namespace

void SimulatedAutopilot::set_mode(FlightMode mode, double now_s, const std::string& why) {
  if (mode == mode_) return;
  if (mode == FlightMode::Land) mode_before_land_ = mode_;
  mode_ = mode;
  hold_height_m_.reset();
  guided_levelled_since_s_.reset();
  land_descent_from_s_.reset();
  if (mode != FlightMode::Land) in_failsafe_ = false;
  log_event(AutopilotEvent::Kind::Mode, now_s,
            std::string("Mode ") + mode_name() + " (" + why + ")");
}

void SimulatedAutopilot::arm(double now_s, const std::string& why) {
  armed_ = true;
  landed_in_land_mode_ = false;
  hold_height_m_.reset();
  auto_disarm_.on_armed(now_s);
  log_event(AutopilotEvent::Kind::Arming, now_s, "Armed (" + why + ")");
  report(Px4Event("commander_armed_by", Px4EventLevel::Info).arg(px4_arm_reason::kExternalCommand),
         now_s);
  say(kSeverityInfo, "Arming motors");
}

// PX4 then shows the mode the landing interrupted again (its user mode intention: OFFBOARD
// after COVER's flight, seen on PX4 SITL); ArduPilot stays in LAND.
void SimulatedAutopilot::disarm(double now_s, const std::string& why, std::uint8_t px4_reason) {
  armed_ = false;
  log_event(AutopilotEvent::Kind::Arming, now_s, "Disarmed (" + why + ")");
  report(Px4Event("commander_disarmed_by", Px4EventLevel::Info).arg(px4_reason), now_s);
  say(kSeverityInfo, "Disarming motors");
  if (mode_ != FlightMode::Land) return;
  landed_in_land_mode_ = true;
  if (profile_ == Autopilot::Px4) set_mode(mode_before_land_, now_s, "after its landing");
}

void SimulatedAutopilot::log_event(AutopilotEvent::Kind kind, double now_s,
                                   const std::string& text) {
  events_.push_back({kind, now_s, text});
}

void SimulatedAutopilot::say(std::uint8_t severity, const std::string& text) {
  if (profile_ != Autopilot::ArduPilot || !link_active_) return;
  mavlink::StatusText status;
  status.severity = severity;
  status.set_text(text);
  queue(status);
}

void SimulatedAutopilot::report(const Px4Event& event, double now_s) {
  if (profile_ != Autopilot::Px4) return;
  queue(event.message(event_sequence_++, boot_ms(now_s)));
}

std::vector<std::string> SimulatedAutopilot::take_link_notes() {
  std::vector<std::string> notes;
  notes.swap(link_notes_);
  return notes;
}

void SimulatedAutopilot::warn_limited(const std::string& text, double now_s) {
  auto it = warned_at_s_.find(text);
  if (it != warned_at_s_.end() && now_s - it->second < 1.0) return;
  warned_at_s_[text] = now_s;
  log_event(AutopilotEvent::Kind::Refusal, now_s, text);
}

}  // namespace cover::sim::fc
