#include "cover/vrpn/client_session.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "big_endian.hpp"

namespace cover::vrpn {
namespace {

// Our own type ids on this connection (the server maps them by the names we describe).
enum LocalType : std::int32_t { kLocalPosQuat = 0, kLocalVelocity, kLocalPing, kLocalPong };

// A position beyond this (in the server's units: 10 km in mm) is a broken sample.
constexpr double kMaxCoordinate = 1e7;
// A quaternion this far from unit length is not a rotation the server meant.
constexpr double kQuaternionNormTolerance = 0.1;

std::string_view name_of(const RawMessage& message, bool* ok) {
  // int32 length (strlen + 1), then the name and its NUL.
  *ok = false;
  if (message.payload_bytes < 5) return {};
  const std::int32_t length = detail::load_i32(message.payload);
  if (length < 1 || static_cast<std::size_t>(length) > message.payload_bytes - 4) return {};
  const char* name = reinterpret_cast<const char*>(message.payload + 4);
  const std::size_t chars = static_cast<std::size_t>(length) - 1;
  if (name[chars] != '\0' || std::memchr(name, '\0', chars) != nullptr) return {};
  *ok = true;
  return {name, chars};
}

bool finite_all(const double* v, int n) {
  for (int i = 0; i < n; ++i) {
    if (!std::isfinite(v[i])) return false;
  }
  return true;
}

}  // namespace

ClientSession::ClientSession(SessionOptions options)
    : options_(std::move(options)), framer_(options_.max_message_bytes) {
  senders_.reserve(options_.max_remote_names);
  types_.reserve(options_.max_remote_names);
  outgoing_.reserve(kCookieBytes + 256 + options_.bodies.size() * 128);
  message_handler_ = [this](const RawMessage& m) { on_message(m, *report_handler_); };
}

void ClientSession::start() {
  framer_.reset();
  cookie_have_ = 0;
  failed_ = false;
  error_.clear();
  senders_.clear();
  types_.clear();
  outgoing_.clear();
  const auto cookie = make_cookie();
  outgoing_.insert(outgoing_.end(), cookie.begin(), cookie.end());
}

void ClientSession::consume_outgoing(std::size_t bytes) {
  outgoing_.erase(outgoing_.begin(), outgoing_.begin() + static_cast<std::ptrdiff_t>(
                                                             std::min(bytes, outgoing_.size())));
}

std::string ClientSession::peer_version() const {
  const auto* text = reinterpret_cast<const char*>(cookie_.data());
  return std::string(text, strnlen(text, kMagic.size()));
}

void ClientSession::fail(const std::string& why) {
  failed_ = true;
  error_ = why;
}

bool ClientSession::feed(const std::uint8_t* data, std::size_t size,
                         const ReportHandler& on_report) {
  if (failed_) return false;
  if (cookie_have_ < kCookieBytes) {
    const std::size_t take = std::min(size, kCookieBytes - cookie_have_);
    std::memcpy(cookie_.data() + cookie_have_, data, take);
    cookie_have_ += take;
    data += take;
    size -= take;
    if (cookie_have_ < kCookieBytes) return true;
    const CookieCheck check = check_cookie(cookie_.data());
    if (check == CookieCheck::Mismatch) {
      ++stats_.bad_cookies;
      fail("not a VRPN 07.x server (its first bytes are not a VRPN cookie)");
      return false;
    }
    minor_mismatch_ = check == CookieCheck::MinorMismatch;
    if (minor_mismatch_) ++stats_.minor_version_mismatches;
    // Our senders (the bodies) and types, so that the server can read our pongs.
    for (std::size_t i = 0; i < options_.bodies.size(); ++i) {
      queue_description(kSenderDescription, static_cast<std::int32_t>(i), options_.bodies[i]);
    }
    queue_description(kTypeDescription, kLocalPosQuat, std::string(kPosQuatType));
    queue_description(kTypeDescription, kLocalVelocity, std::string(kVelocityType));
    queue_description(kTypeDescription, kLocalPing, std::string(kPingType));
    queue_description(kTypeDescription, kLocalPong, std::string(kPongType));
  }
  report_handler_ = &on_report;
  if (!framer_.feed(data, size, message_handler_)) {
    ++stats_.bad_lengths;
    fail("stream out of step: a message length of " + std::to_string(framer_.bad_length()) +
         " bytes (accepted: " + std::to_string(kHeaderBytes) + ".." +
         std::to_string(options_.max_message_bytes) + ")");
    return false;
  }
  return true;
}

const ClientSession::RemoteName* ClientSession::find(const std::vector<RemoteName>& table,
                                                     std::int32_t id) {
  for (const RemoteName& entry : table) {
    if (entry.id == id) return &entry;
  }
  return nullptr;
}

void ClientSession::on_message(const RawMessage& message, const ReportHandler& on_report) {
  ++stats_.messages;
  if (message.type == kSenderDescription) return on_description(message, senders_, true);
  if (message.type == kTypeDescription) return on_description(message, types_, false);
  if (message.type < 0) return;  // UDP / log descriptions, disconnect: nothing for TCP alone
  const RemoteName* type = find(types_, message.type);
  if (!type) {
    ++stats_.unknown_type;
    return;
  }
  const auto kind = static_cast<TypeKind>(type->value);
  if (kind == TypeKind::Other) return;  // another device's message: not ours to read
  const RemoteName* sender = find(senders_, message.sender);
  if (!sender) {
    ++stats_.unknown_sender;
    return;
  }
  if (sender->value < 0) {
    if (kind != TypeKind::Ping) ++stats_.untracked;
    return;
  }
  if (kind == TypeKind::Ping) return answer_ping(message, sender->value);
  on_tracker(message, sender->value, kind, on_report);
}

void ClientSession::on_description(const RawMessage& message, std::vector<RemoteName>& table,
                                   bool is_sender) {
  bool ok = false;
  const std::string_view name = name_of(message, &ok);
  if (!ok) {
    ++stats_.bad_descriptions;
    return;
  }
  RemoteName entry;
  // Both descriptions carry the described id in the sender field (vrpn_Connection.C
  // pack_type_description: "whose sender ID is the ID of the type").
  entry.id = message.sender;
  if (is_sender) {
    const auto& bodies = options_.bodies;
    const auto it = std::find(bodies.begin(), bodies.end(), name);
    entry.value = it == bodies.end() ? -1 : static_cast<std::int16_t>(it - bodies.begin());
  } else {
    TypeKind kind = TypeKind::Other;
    if (name == kPosQuatType) kind = TypeKind::PosQuat;
    if (name == kVelocityType) kind = TypeKind::Velocity;
    if (name == kPingType) kind = TypeKind::Ping;
    entry.value = static_cast<std::int16_t>(kind);
  }
  // A re-description of an id replaces it.
  for (RemoteName& existing : table) {
    if (existing.id == entry.id) {
      existing = entry;
      return;
    }
  }
  if (table.size() >= options_.max_remote_names) {
    ++stats_.names_overflow;
    return;
  }
  table.push_back(entry);
}

void ClientSession::on_tracker(const RawMessage& message, int body, TypeKind kind,
                               const ReportHandler& on_report) {
  const std::size_t expected = kind == TypeKind::PosQuat ? kPosQuatBytes : kVelocityBytes;
  if (message.payload_bytes != expected) {
    ++stats_.wrong_size;
    return;
  }
  TrackerReport report;
  report.body = body;
  report.sensor = detail::load_i32(message.payload);
  report.time = message.time;
  report.kind =
      kind == TypeKind::PosQuat ? TrackerReport::Kind::Pose : TrackerReport::Kind::Velocity;
  double values[7];
  for (int i = 0; i < 7; ++i) values[i] = detail::load_f64(message.payload + 8 + 8 * i);
  bool valid = finite_all(values, 7) && std::abs(values[0]) < kMaxCoordinate &&
               std::abs(values[1]) < kMaxCoordinate && std::abs(values[2]) < kMaxCoordinate;
  if (valid && report.kind == TrackerReport::Kind::Pose) {
    const double norm = std::sqrt(values[3] * values[3] + values[4] * values[4] +
                                  values[5] * values[5] + values[6] * values[6]);
    valid = std::abs(norm - 1.0) < kQuaternionNormTolerance;
    for (int i = 3; i < 7 && valid; ++i) values[i] /= norm;
  }
  report.valid = valid;
  if (valid) {
    std::copy(values, values + 3, report.position.begin());
    std::copy(values + 3, values + 7, report.quaternion_xyzw.begin());
    ++(report.kind == TrackerReport::Kind::Pose ? stats_.poses : stats_.velocities);
  } else {
    ++stats_.lost_samples;
  }
  on_report(report);
}

void ClientSession::answer_ping(const RawMessage& message, int body) {
  ++stats_.pings_answered;
  queue_message(body, kLocalPong, message.time, nullptr, 0);
}

void ClientSession::queue_ping(ServerTime now) {
  if (handshake_done()) queue_message(0, kLocalPing, now, nullptr, 0);
}

void ClientSession::queue_message(std::int32_t sender, std::int32_t type, ServerTime time,
                                  const std::uint8_t* payload, std::size_t bytes) {
  std::uint8_t header[kHeaderBytes] = {};
  detail::store_u32(header, static_cast<std::uint32_t>(kHeaderBytes + bytes));
  detail::store_i32(header + 4, time.seconds);
  detail::store_i32(header + 8, time.microseconds);
  detail::store_i32(header + 12, sender);
  detail::store_i32(header + 16, type);
  outgoing_.insert(outgoing_.end(), header, header + kHeaderBytes);
  if (bytes > 0) outgoing_.insert(outgoing_.end(), payload, payload + bytes);
  outgoing_.resize(outgoing_.size() + (ceil8(bytes) - bytes), 0);
}

void ClientSession::queue_description(std::int32_t system_type, std::int32_t id,
                                      const std::string& name) {
  std::vector<std::uint8_t> payload(4 + name.size() + 1, 0);
  detail::store_u32(payload.data(), static_cast<std::uint32_t>(name.size() + 1));
  std::memcpy(payload.data() + 4, name.data(), name.size());
  queue_message(id, system_type, ServerTime{}, payload.data(), payload.size());
}

}  // namespace cover::vrpn
