// Built as C++17: websocketpp 0.8.2 does not compile as C++20 (CMakeLists.txt).
#define ASIO_STANDALONE
#include "skyfuse/live/live_server.hpp"

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <fstream>
#include <map>
#include <mutex>
#include <set>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <websocketpp/config/asio_no_tls.hpp>
#include <websocketpp/server.hpp>

#include "skyfuse/live/background_priority.hpp"

namespace skyfuse::live {
namespace {

using Server = websocketpp::server<websocketpp::config::asio>;
using Handle = websocketpp::connection_hdl;

std::string content_type(const std::string& path) {
  const auto ends = [&](const char* suffix) {
    const std::string s(suffix);
    return path.size() >= s.size() && path.compare(path.size() - s.size(), s.size(), s) == 0;
  };
  if (ends(".html")) return "text/html; charset=utf-8";
  if (ends(".js")) return "text/javascript; charset=utf-8";
  if (ends(".css")) return "text/css; charset=utf-8";
  if (ends(".json")) return "application/json";
  if (ends(".png")) return "image/png";
  if (ends(".svg")) return "image/svg+xml";
  if (ends(".mcap")) return "application/x-mcap";
  return "application/octet-stream";
}

}  // namespace

struct LiveServer::Impl {
  Options options;
  std::vector<AdvertisedChannel> channels;
  Server server;
  std::thread thread;
  std::uint16_t port = 0;

  // Touched on the server's thread only.
  struct Client {
    std::map<std::uint32_t, std::set<std::uint32_t>> subscriptions_by_channel;
    std::map<std::uint32_t, std::uint32_t> channel_of_subscription;
  };
  std::map<Handle, Client, std::owner_less<Handle>> clients;
  std::uint64_t sessions = 0;  ///< connections opened so far: each client's session id

  std::atomic<std::size_t> connected{0};
  std::atomic<std::uint64_t> dropped{0};
  std::atomic<std::uint64_t> frames{0};
  std::atomic<std::uint64_t> refused{0};
  std::atomic<std::size_t> subscriptions{0};  ///< over every client: a copy for other threads
  std::atomic<std::uint64_t> posted{0};
  std::atomic<std::uint64_t> handled{0};

  void count_subscriptions() {
    std::size_t n = 0;
    for (const auto& [h, client] : clients) n += client.channel_of_subscription.size();
    subscriptions = n;
  }

  void send_text(Handle h, const std::string& text) {
    websocketpp::lib::error_code ec;
    server.send(h, text, websocketpp::frame::opcode::text, ec);
  }

  void refuse(Handle h, const std::string& why) {
    ++refused;
    send_text(h, status(StatusLevel::kError, why));
  }

  void on_message(Handle h, Server::message_ptr message) {
    const auto it = clients.find(h);
    if (it == clients.end()) return;
    if (message->get_opcode() != websocketpp::frame::opcode::text) {
      refuse(h, refuse_client_binary(message->get_payload()).why);
      return;
    }
    const ClientRequest request = parse_client_text(message->get_payload());
    Client& client = it->second;
    if (const auto* s = std::get_if<Subscribe>(&request)) {
      for (const auto& [id, channel] : s->subscriptions) {
        if (channel >= channels.size()) {
          refuse(h, "subscribe: no channel " + std::to_string(channel) + ": ignored");
          continue;
        }
        if (client.channel_of_subscription.count(id) != 0) {
          refuse(h, "subscribe: subscription id " + std::to_string(id) + " is in use: ignored");
          continue;
        }
        client.channel_of_subscription[id] = channel;
        client.subscriptions_by_channel[channel].insert(id);
      }
    } else if (const auto* u = std::get_if<Unsubscribe>(&request)) {
      for (std::uint32_t id : u->subscription_ids) {
        const auto sub = client.channel_of_subscription.find(id);
        if (sub == client.channel_of_subscription.end()) continue;
        client.subscriptions_by_channel[sub->second].erase(id);
        client.channel_of_subscription.erase(sub);
      }
    } else {
      refuse(h, std::get<Refused>(request).why);
    }
    count_subscriptions();
  }

  void on_http(Handle h) {
    const Server::connection_ptr con = server.get_con_from_hdl(h);
    std::string path = con->get_resource();
    path = path.substr(0, path.find('?'));
    if (path == "/") path = "/index.html";
    const auto named = options.files.find(path);
    if (named == options.files.end() && options.site_dir.empty()) {
      con->set_status(websocketpp::http::status_code::ok);
      con->append_header("Content-Type", "text/plain; charset=utf-8");
      con->set_body("skyfuse live: connect a Foxglove WebSocket client (foxglove.websocket.v1)\n");
      return;
    }
    std::ifstream in;
    if (named != options.files.end()) {
      in.open(named->second, std::ios::binary);
    } else if (path.find("..") == std::string::npos) {
      in.open(options.site_dir + path, std::ios::binary);
    }
    if (!in) {
      con->set_status(websocketpp::http::status_code::not_found);
      con->set_body("not found\n");
      return;
    }
    std::ostringstream body;
    body << in.rdbuf();
    con->set_status(websocketpp::http::status_code::ok);
    con->append_header("Content-Type", content_type(path));
    con->append_header("Cache-Control", "no-store");
    con->set_body(body.str());
  }

  bool on_validate(Handle h) {
    const Server::connection_ptr con = server.get_con_from_hdl(h);
    for (const std::string_view wanted : {kSubprotocol, kSdkSubprotocol}) {
      for (const std::string& offered : con->get_requested_subprotocols()) {
        if (offered == wanted) {
          con->select_subprotocol(offered);
          return true;
        }
      }
    }
    return false;  // not a Foxglove client: the handshake is refused
  }

  void on_open(Handle h) {
    clients.emplace(h, Client{});
    ++connected;
    send_text(h, server_info("skyfuse", "skyfuse-" + std::to_string(++sessions)));
    send_text(h, advertise(channels));
  }

  void on_close(Handle h) {
    if (clients.erase(h) != 0) --connected;
    count_subscriptions();
  }

  // On the server's thread: one message to every subscriber, or the end of a slow client.
  void deliver(std::uint32_t channel, std::uint64_t ns, const std::string& payload) {
    std::vector<Handle> too_slow;
    for (auto& [h, client] : clients) {
      const auto subs = client.subscriptions_by_channel.find(channel);
      if (subs == client.subscriptions_by_channel.end() || subs->second.empty()) continue;
      websocketpp::lib::error_code ec;
      const Server::connection_ptr con = server.get_con_from_hdl(h, ec);
      if (ec) continue;
      if (con->get_buffered_amount() > options.client_buffer_bytes) {
        too_slow.push_back(h);
        continue;
      }
      for (std::uint32_t sub : subs->second) {
        server.send(h, message_frame(sub, ns, payload), websocketpp::frame::opcode::binary, ec);
        if (!ec) ++frames;
      }
    }
    for (Handle h : too_slow) {
      websocketpp::lib::error_code ec;
      server.close(h, websocketpp::close::status::policy_violation,
                   "too slow: more than the send buffer behind", ec);
      if (clients.erase(h) != 0) {
        --connected;
        ++dropped;
      }
    }
    if (!too_slow.empty()) count_subscriptions();
  }
};

LiveServer::LiveServer(Options options, std::vector<AdvertisedChannel> channels)
    : impl_(std::make_unique<Impl>()) {
  Impl& d = *impl_;
  d.options = std::move(options);
  d.channels = std::move(channels);
  d.server.clear_access_channels(websocketpp::log::alevel::all);
  d.server.clear_error_channels(websocketpp::log::elevel::all);
  d.server.init_asio();
  d.server.set_reuse_addr(true);
  d.server.set_validate_handler([&d](Handle h) { return d.on_validate(h); });
  d.server.set_open_handler([&d](Handle h) { d.on_open(h); });
  d.server.set_close_handler([&d](Handle h) { d.on_close(h); });
  d.server.set_fail_handler([&d](Handle h) { d.on_close(h); });
  d.server.set_message_handler([&d](Handle h, Server::message_ptr m) { d.on_message(h, m); });
  d.server.set_http_handler([&d](Handle h) { d.on_http(h); });
  const std::string where = d.options.address + ":" + std::to_string(d.options.port);
  try {
    asio::error_code ec;
    const auto address = asio::ip::make_address(d.options.address, ec);
    if (ec) throw std::runtime_error("not an IP address");
    d.server.listen(asio::ip::tcp::endpoint(address, d.options.port));
    d.server.start_accept();
    d.port = d.server.get_local_endpoint(ec).port();
  } catch (const std::exception& e) {
    throw std::runtime_error("--live: cannot listen on " + where + ": " + e.what());
  }
  d.thread = std::thread([&d] {
    lower_this_thread_to_idle_priority();
    d.server.run();
  });
}

LiveServer::~LiveServer() {
  Impl& d = *impl_;
  asio::post(d.server.get_io_service(), [&d] {
    websocketpp::lib::error_code ec;
    d.server.stop_listening(ec);
    for (auto& [h, client] : d.clients) {
      d.server.close(h, websocketpp::close::status::going_away, "the run has ended", ec);
    }
  });
  // Closing handshakes take a moment; then stop whatever is left.
  for (int i = 0; i < 100 && d.connected.load() > 0; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  d.server.stop();
  if (d.thread.joinable()) d.thread.join();
}

std::uint16_t LiveServer::port() const {
  return impl_->port;
}

void LiveServer::publish(std::vector<Message> messages) {
  if (messages.empty()) return;
  Impl& d = *impl_;
  ++d.posted;
  asio::post(d.server.get_io_service(), [&d, messages = std::move(messages)] {
    for (const Message& m : messages) d.deliver(m.channel, m.log_time_ns, m.payload);
    ++d.handled;
  });
}

bool LiveServer::has_subscribers() const {
  return impl_->subscriptions.load() != 0;
}

bool LiveServer::flush(int timeout_ms) {
  const Impl& d = *impl_;
  const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
  const std::uint64_t target = d.posted.load();
  while (std::chrono::steady_clock::now() < until) {
    if (d.handled.load() >= target) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return d.handled.load() >= target;
}

LiveServer::Stats LiveServer::stats() const {
  const Impl& d = *impl_;
  return {d.connected.load(), d.dropped.load(), d.frames.load(), d.refused.load()};
}

}  // namespace skyfuse::live
