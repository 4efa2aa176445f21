#pragma once
// The Foxglove WebSocket protocol (github.com/foxglove/ws-protocol, docs/spec.md), server side,
// as skyfuse speaks it: it only publishes. JSON text messages for the session (serverInfo,
// advertise, status) and the client's subscribe and unsubscribe; binary frames for messages:
// 0x01, u32 subscription id, u64 log time in ns, payload, little-endian. No sockets here, so
// that every rule can be tested without a network.

#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

namespace skyfuse::live {

/// The subprotocols skyfuse accepts, in order of preference.
inline constexpr std::string_view kSubprotocol = "foxglove.websocket.v1";
inline constexpr std::string_view kSdkSubprotocol = "foxglove.sdk.v1";

struct AdvertisedChannel {
  std::uint32_t id = 0;
  std::string topic;
  std::string schema_name;
  std::string schema;  ///< JSON schema text
};

/// Status levels of the protocol's status message.
enum class StatusLevel { kInfo = 0, kWarning = 1, kError = 2 };

std::string server_info(std::string_view name, std::string_view session_id);
std::string advertise(const std::vector<AdvertisedChannel>& channels);
std::string status(StatusLevel level, std::string_view message);
/// The binary frame of one message for subscription `subscription`.
std::string message_frame(std::uint32_t subscription, std::uint64_t log_time_ns,
                          std::string_view payload);

/// What a client's text message asks for.
struct Subscribe {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> subscriptions;  ///< (id, channel id)
};
struct Unsubscribe {
  std::vector<std::uint32_t> subscription_ids;
};
/// A well-formed request skyfuse does not serve (client publishing, services, parameters, ...),
/// or a message that is not a request at all; `why` is the status message's text.
struct Refused {
  std::string why;
};
using ClientRequest = std::variant<Subscribe, Unsubscribe, Refused>;

ClientRequest parse_client_text(std::string_view text);
/// A client's binary message: skyfuse takes none (they publish or call services).
Refused refuse_client_binary(std::string_view bytes);

}  // namespace skyfuse::live
