#include "skyfuse/live/ws_protocol.hpp"

#include <nlohmann/json.hpp>

#include "skyfuse/record/little_endian.hpp"

namespace skyfuse::live {
namespace {

using nlohmann::json;

// A JSON number that is a whole number in [0, 2^32): ids in the protocol.
bool is_u32(const json& v) {
  return v.is_number_unsigned() && v.get<std::uint64_t>() <= 0xFFFFFFFFu;
}

}  // namespace

std::string server_info(std::string_view name, std::string_view session_id) {
  return json{{"op", "serverInfo"},
              {"name", name},
              {"capabilities", json::array()},  // none: no client publish, services, params
              {"supportedEncodings", json::array()},
              {"metadata", json::object()},
              {"sessionId", session_id}}
      .dump();
}

std::string advertise(const std::vector<AdvertisedChannel>& channels) {
  json list = json::array();
  for (const AdvertisedChannel& c : channels) {
    list.push_back({{"id", c.id},
                    {"topic", c.topic},
                    {"encoding", "json"},
                    {"schemaName", c.schema_name},
                    {"schema", c.schema},
                    {"schemaEncoding", "jsonschema"}});
  }
  return json{{"op", "advertise"}, {"channels", std::move(list)}}.dump();
}

std::string status(StatusLevel level, std::string_view message) {
  return json{{"op", "status"}, {"level", static_cast<int>(level)}, {"message", message}}.dump();
}

std::string message_frame(std::uint32_t subscription, std::uint64_t log_time_ns,
                          std::string_view payload) {
  std::string frame;
  frame.reserve(13 + payload.size());
  record::append_little_endian(frame, std::uint8_t{0x01});
  record::append_little_endian(frame, subscription);
  record::append_little_endian(frame, log_time_ns);
  frame.append(payload);
  return frame;
}

ClientRequest parse_client_text(std::string_view text) {
  const json message = json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (message.is_discarded()) return Refused{"not JSON: ignored"};
  if (!message.is_object() || !message.contains("op") || !message["op"].is_string()) {
    return Refused{"a message without a string 'op': ignored"};
  }
  const std::string op = message["op"].get<std::string>();
  if (op == "subscribe") {
    const auto it = message.find("subscriptions");
    if (it == message.end() || !it->is_array()) {
      return Refused{"subscribe: 'subscriptions' must be an array: ignored"};
    }
    Subscribe s;
    for (const json& entry : *it) {
      if (!entry.is_object() || !entry.contains("id") || !entry.contains("channelId") ||
          !is_u32(entry["id"]) || !is_u32(entry["channelId"])) {
        return Refused{
            "subscribe: each subscription needs whole-number 'id' and 'channelId': "
            "ignored"};
      }
      s.subscriptions.emplace_back(entry["id"].get<std::uint32_t>(),
                                   entry["channelId"].get<std::uint32_t>());
    }
    return s;
  }
  if (op == "unsubscribe") {
    const auto it = message.find("subscriptionIds");
    if (it == message.end() || !it->is_array()) {
      return Refused{"unsubscribe: 'subscriptionIds' must be an array: ignored"};
    }
    Unsubscribe u;
    for (const json& id : *it) {
      if (!is_u32(id)) return Refused{"unsubscribe: ids must be whole numbers: ignored"};
      u.subscription_ids.push_back(id.get<std::uint32_t>());
    }
    return u;
  }
  return Refused{"'" + op + "' is not served: skyfuse only publishes (no client channels, " +
                 "services or parameters)"};
}

Refused refuse_client_binary(std::string_view bytes) {
  const int op = bytes.empty() ? -1 : static_cast<unsigned char>(bytes[0]);
  return Refused{"binary message (opcode " + std::to_string(op) +
                 ") not served: skyfuse only publishes"};
}

}  // namespace skyfuse::live
