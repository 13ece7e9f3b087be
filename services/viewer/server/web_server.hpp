#pragma once
/// @file
/// The viewer's HTTP and WebSocket server (civetweb): static files of the bundled page, a few
/// handlers for data, and one WebSocket endpoint (/ws) on which every client gets the latest
/// messages. Sending is latest value wins per channel on a thread of its own: a slow or stuck
/// browser never blocks the caller, it only misses frames.

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <vector>

struct mg_context;
struct mg_connection;

namespace climbsim::viewer {

/// The answer of an HTTP handler.
struct HttpResponse {
  int status = 200;
  std::string content_type = "application/json";
  std::string body;
};

/// Handles GET <prefix>...: gets the path after the host and the query string (without '?').
using HttpHandler = std::function<HttpResponse(const std::string& path, const std::string& query)>;

/// A WebSocket text message from a client; false: garbage, the client is disconnected.
using ClientMessageHandler = std::function<bool(const std::string& text)>;

class WebServer {
 public:
  struct Options {
    std::string bind = "127.0.0.1";  ///< IPv4 address to listen on ("0.0.0.0": every interface)
    int port = 8765;                 ///< TCP port, 1..65535
    /// Ports tried from `port` on while they are taken (by another run's viewer): 1 takes
    /// `port` or fails; N takes the first free one of port .. port + N - 1.
    int port_tries = 1;
    std::string web_dir;             ///< the bundled page (index.html, viewer.js, viewer.css)
  };

  /// Listens at once; throws ConfigError with one line naming the port or address that
  /// cannot be used (checkBindable; the last port tried), or naming web_dir if it has no
  /// index.html. port() and url() give the port taken.
  explicit WebServer(const Options& options);
  ~WebServer();
  WebServer(const WebServer&) = delete;
  WebServer& operator=(const WebServer&) = delete;

  /// Routes GET requests whose path starts with `prefix` (e.g. "/api/") to `handler`. Call
  /// before clients come (not synchronised with requests).
  void handle(const std::string& prefix, HttpHandler handler);

  /// What a client's text messages do (default: every message is garbage).
  void onClientMessage(ClientMessageHandler handler);

  /// Sets the latest message of `channel` and sends it to every client (latest value wins:
  /// a message not yet sent when the next one comes is replaced). A client that connects
  /// later gets the latest message of every channel, in channel-name order.
  void publish(const std::string& channel, std::string text);

  /// Clients connected now.
  int clientCount() const;
  /// Messages sent, per client summed (diagnostics, tests).
  std::uint64_t messagesSent() const { return sent_; }
  /// Clients disconnected for sending garbage.
  std::uint64_t clientsDropped() const { return dropped_; }

  /// http://<bind>:<port>/ (with the machine's host name for 0.0.0.0).
  std::string url() const;
  /// The port it listens on (Options::port, or a later one of port_tries).
  int port() const { return options_.port; }

 private:
  struct Client;
  static int dispatch(mg_connection* conn, void* self);
  static int wsConnect(const mg_connection* conn, void* self);
  static void wsReady(mg_connection* conn, void* self);
  static int wsData(mg_connection* conn, int bits, char* data, std::size_t length, void* self);
  static void wsClose(const mg_connection* conn, void* self);
  void sendLoop();
  /// civetweb listening on options_.bind:options_.port; nullptr if it cannot.
  mg_context* start();

  Options options_;
  mg_context* context_ = nullptr;
  std::vector<std::pair<std::string, HttpHandler>> handlers_;
  ClientMessageHandler on_message_;

  mutable std::mutex mutex_;
  std::condition_variable wake_;
  bool quit_ = false;
  std::map<std::string, std::shared_ptr<const std::string>> latest_;  ///< channel -> message
  std::uint64_t version_ = 0;                                          ///< bumps with every publish
  std::map<const mg_connection*, std::shared_ptr<Client>> clients_;
  std::atomic<std::uint64_t> sent_{0};
  std::atomic<std::uint64_t> dropped_{0};
  std::thread sender_;
};

}  // namespace climbsim::viewer
