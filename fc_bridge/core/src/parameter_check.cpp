#include "cover/fc_bridge/parameter_check.hpp"

#include <cmath>
#include <cstdio>

namespace cover::fc_bridge {

const char* to_string(ParameterWeight weight) {
  switch (weight) {
    case ParameterWeight::Blocking:
      return "blocking";
    case ParameterWeight::Advisory:
      return "advisory";
    case ParameterWeight::Info:
      return "info";
  }
  return "info";
}

ParameterCheck::ParameterCheck(std::vector<ParameterRule> rules, mavlink::ParamEncoding encoding,
                               double timeout_s, int tries, double refresh_s)
    : rules_(std::move(rules)),
      encoding_(encoding),
      timeout_s_(timeout_s),
      tries_(tries),
      refresh_s_(refresh_s) {
  findings_.reserve(rules_.size());
  for (const ParameterRule& rule : rules_) {
    ParameterFinding finding;
    finding.name = rule.names.front();
    finding.weight = rule.weight;
    finding.needed = rule.needed;
    finding.why = rule.why;
    findings_.push_back(finding);
  }
  readings_.resize(rules_.size());
}

void ParameterCheck::restart(double now_s) {
  for (std::size_t i = 0; i < rules_.size(); ++i) {
    const ParameterRule& rule = rules_[i];
    findings_[i].name = rule.names.front();
    findings_[i].known = false;
    findings_[i].absent = false;
    findings_[i].ok = true;
    readings_[i] = Reading{};
  }
  round_start_s_ = now_s;
  round_started_ = true;
  complete_once_ = false;
}

void ParameterCheck::set_context(const ParameterContext& context) {
  context_ = context;
  for (std::size_t i = 0; i < rules_.size(); ++i) {
    if (findings_[i].known) judge(i, findings_[i].name, findings_[i].value);
  }
}

std::optional<mavlink::ParamRequestRead> ParameterCheck::next_request(double now_s) {
  if (!round_started_) return std::nullopt;
  if (complete() && now_s - round_start_s_ >= refresh_s_) {
    for (Reading& reading : readings_) reading = Reading{};  // values stay until answered
    round_start_s_ = now_s;
  }
  for (std::size_t i = 0; i < readings_.size(); ++i) {
    Reading& reading = readings_[i];
    if (reading.done) continue;
    if (reading.deadline_s >= 0.0 && now_s < reading.deadline_s) continue;  // in flight
    if (reading.tries >= tries_) {  // this name never answered: the next, or absent
      reading.tries = 0;
      if (++reading.name_index >= rules_[i].names.size()) {
        reading.done = true;
        findings_[i].known = false;
        findings_[i].absent = true;
        findings_[i].ok = rules_[i].weight == ParameterWeight::Info;
        complete_once_ = complete_once_ || complete();
        continue;
      }
    }
    ++reading.tries;
    reading.deadline_s = now_s + timeout_s_;
    mavlink::ParamRequestRead request;
    request.param_index = -1;
    request.param_id = mavlink::param_id_from(rules_[i].names[reading.name_index]);
    return request;
  }
  return std::nullopt;
}

bool ParameterCheck::on_value(const mavlink::ParamValue& value, double now_s) {
  (void)now_s;
  const std::string name = mavlink::param_id_string(value.param_id);
  for (std::size_t i = 0; i < rules_.size(); ++i) {
    for (const std::string& candidate : rules_[i].names) {
      if (candidate != name) continue;
      readings_[i].done = true;
      readings_[i].deadline_s = -1.0;
      const double number = mavlink::param_value_of(value.param_value, value.param_type, encoding_);
      const bool news = !findings_[i].known || findings_[i].value != number;
      judge(i, name, number);
      complete_once_ = complete_once_ || complete();
      return news;
    }
  }
  return false;
}

void ParameterCheck::judge(std::size_t index, const std::string& name, double value) {
  ParameterFinding& finding = findings_[index];
  finding.name = name;
  finding.known = std::isfinite(value);
  finding.absent = false;
  finding.value = value;
  const ParameterRule& rule = rules_[index];
  finding.ok = finding.known && (rule.acceptable == nullptr || rule.acceptable(value)) &&
               (rule.acceptable_on_link == nullptr || rule.acceptable_on_link(value, context_));
}

bool ParameterCheck::complete() const {
  if (complete_once_) return true;
  for (const Reading& reading : readings_) {
    if (!reading.done) return false;
  }
  return !readings_.empty();
}

std::string ParameterCheck::flight_blocker() const {
  for (const ParameterFinding& finding : findings_) {
    if (finding.weight != ParameterWeight::Blocking || finding.ok || !finding.known) continue;
    char value[32];
    std::snprintf(value, sizeof value, "%g", finding.value);
    return "autopilot parameter " + finding.name + " is " + value + ", COVER needs " +
           finding.needed + ": " + finding.why;
  }
  return "";
}

std::optional<double> ParameterCheck::value(const std::string& name) const {
  for (std::size_t i = 0; i < rules_.size(); ++i) {
    for (const std::string& candidate : rules_[i].names) {
      if (candidate == name && findings_[i].known) return findings_[i].value;
    }
  }
  return std::nullopt;
}

}  // namespace cover::fc_bridge
