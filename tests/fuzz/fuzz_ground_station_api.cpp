// cover-ground-station's API parser (cover_ground_station_api), fed any bytes a page can send
// in a WebSocket text message, and the access rules fed any request target and headers.
// Contract: no crash, no exception; an Invalid request says why; a Submit's task passed the
// task file's checks (UGV ids within the fleet); the reply sent back is valid JSON whatever
// bytes the reason quotes; the same bytes parse the same way twice; a static file name never
// climbs out of the served folder.
#include <nlohmann/json.hpp>

#include <algorithm>
#include <string>
#include <string_view>

#include "cover/ground_station/access.hpp"
#include "cover/ground_station/api.hpp"
#include "fuzz_input.hpp"

namespace {

namespace gs = cover::ground_station;
using cover::fuzz::require;

void check(const gs::ApiRequest& r) {
  if (r.op == gs::ApiOp::Invalid) require(!r.error.empty(), "an invalid request says why");
  if (r.op == gs::ApiOp::Submit) {
    require(!r.task.processes.empty(), "a submitted task has processes");
    for (const auto& p : r.task.processes)
      require(p.from_ugv >= 0 && p.from_ugv < 2 && p.to_ugv >= 0 && p.to_ugv < 2,
              "UGV ids in the fleet");
  }
  if (r.op == gs::ApiOp::Abort) require(!r.task_id.empty(), "an abort names its task");
  require(r.id.size() <= gs::kMaxIdBytes, "id bounded");
  const auto reply = nlohmann::json::parse(
      gs::reply_json(r.id, r.op != gs::ApiOp::Invalid, r.error, r.field), nullptr, false);
  require(!reply.is_discarded(), "the reply is JSON");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const gs::ApiRequest first = gs::parse_request(text, 2);
  check(first);
  const gs::ApiRequest again = gs::parse_request(text, 2);
  require(first.op == again.op && first.error == again.error && first.id == again.id,
          "the same bytes parse the same way");
  const std::string target(text.substr(0, std::min<std::size_t>(size, 512)));
  if (const auto file = gs::static_file(target)) {
    require(!file->empty() && (*file)[0] != '/' && (*file)[0] != '.' &&
                file->find("/.") == std::string::npos && file->find("//") == std::string::npos,
            "relative, no parent folder, nothing hidden");
  }
  gs::AccessPolicy policy{"0123456789abcdef0123456789abcdef", true};
  const auto d = gs::check_request(policy, target, target, "127.0.0.1:8080", target);
  require(d.status == 200 || d.status == 401 || d.status == 403 || d.status == 400,
          "a known status");
  require(d.status != 200 || d.has_token, "the network needs the token");
  return 0;
}
