// The Foxglove WebSocket protocol as skyfuse serves it (github.com/foxglove/ws-protocol,
// docs/spec.md): its session messages, the binary message frame byte by byte, and the client
// requests it takes (subscribe, unsubscribe) or answers with a refusal. tests/view's live test
// speaks to the real server with the protocol's own JavaScript client.
#include "skyfuse/live/ws_protocol.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

namespace skyfuse::live {
namespace {

using nlohmann::json;

TEST(WsProtocol, AdvertisesJsonChannelsWithTheirSchemas) {
  const json info = json::parse(server_info("skyfuse", "s-1"));
  EXPECT_EQ(info["op"], "serverInfo");
  EXPECT_EQ(info["capabilities"], json::array()) << "no client publish, services or parameters";
  const json ad = json::parse(advertise({{7, "/scene", "foxglove.SceneUpdate", "{}"}}));
  EXPECT_EQ(ad["op"], "advertise");
  ASSERT_EQ(ad["channels"].size(), 1u);
  EXPECT_EQ(ad["channels"][0]["id"], 7);
  EXPECT_EQ(ad["channels"][0]["topic"], "/scene");
  EXPECT_EQ(ad["channels"][0]["encoding"], "json");
  EXPECT_EQ(ad["channels"][0]["schemaName"], "foxglove.SceneUpdate");
  EXPECT_EQ(ad["channels"][0]["schemaEncoding"], "jsonschema");
  const json s = json::parse(status(StatusLevel::kError, "no"));
  EXPECT_EQ(s["op"], "status");
  EXPECT_EQ(s["level"], 2);
}

TEST(WsProtocol, AMessageFrameIsOpcodeSubscriptionTimeAndPayloadLittleEndian) {
  const std::string frame = message_frame(0x04030201u, 0x0C0B0A0908070605ull, "{}");
  const std::string expected("\x01\x01\x02\x03\x04\x05\x06\x07\x08\x09\x0A\x0B\x0C{}", 15);
  EXPECT_EQ(frame, expected);
}

TEST(WsProtocol, TakesSubscribeAndUnsubscribe) {
  const ClientRequest s = parse_client_text(
      R"({"op":"subscribe","subscriptions":[{"id":1,"channelId":0},{"id":2,"channelId":5}]})");
  ASSERT_TRUE(std::holds_alternative<Subscribe>(s));
  const auto& pairs = std::get<Subscribe>(s).subscriptions;
  ASSERT_EQ(pairs.size(), 2u);
  EXPECT_EQ(pairs[1], (std::pair<std::uint32_t, std::uint32_t>{2, 5}));
  const ClientRequest u = parse_client_text(R"({"op":"unsubscribe","subscriptionIds":[2]})");
  ASSERT_TRUE(std::holds_alternative<Unsubscribe>(u));
  EXPECT_EQ(std::get<Unsubscribe>(u).subscription_ids, std::vector<std::uint32_t>{2});
}

TEST(WsProtocol, RefusesWhatItDoesNotServeAndWhatIsMalformed) {
  for (const char* text : {
           "not json",
           "[1,2]",
           R"({"op":3})",
           R"({"op":"subscribe"})",
           R"({"op":"subscribe","subscriptions":[{"id":-1,"channelId":0}]})",
           R"({"op":"subscribe","subscriptions":[{"id":4294967296,"channelId":0}]})",
           R"({"op":"unsubscribe","subscriptionIds":["a"]})",
           R"({"op":"advertise","channels":[]})",
           R"({"op":"getParameters","parameterNames":[]})",
           R"({"op":"setParameters","parameters":[]})",
           R"({"op":"subscribeConnectionGraph"})",
       }) {
    const ClientRequest r = parse_client_text(text);
    ASSERT_TRUE(std::holds_alternative<Refused>(r)) << text;
    EXPECT_FALSE(std::get<Refused>(r).why.empty()) << text;
  }
  EXPECT_NE(
      std::get<Refused>(parse_client_text(R"({"op":"advertise"})")).why.find("only publishes"),
      std::string::npos);
  EXPECT_NE(refuse_client_binary(std::string("\x02", 1)).why.find("opcode 2"), std::string::npos);
}

}  // namespace
}  // namespace skyfuse::live
