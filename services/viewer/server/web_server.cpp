#include "web_server.hpp"

#include <unistd.h>

#include <algorithm>
#include <filesystem>

#include <civetweb.h>
#include <spdlog/spdlog.h>

#include "bind_check.hpp"
#include "climbsim/errors.hpp"

namespace climbsim::viewer {

/// A connected WebSocket client and what it has been sent.
struct WebServer::Client {
  mg_connection* conn = nullptr;
  bool ready = false;                                              ///< handshake done
  std::mutex write_mutex;  ///< held while writing; the close handler takes it, so conn outlives a write
  bool closed = false;     ///< under write_mutex
  std::map<std::string, std::shared_ptr<const std::string>> sent;  ///< channel -> last message sent
};

WebServer::WebServer(const Options& options) : options_(options) {
  if (!std::filesystem::exists(std::filesystem::path(options.web_dir) / "index.html")) {
    throw ConfigError("--web-dir " + options.web_dir + ": no index.html (is the viewer's page built?)");
  }
  mg_init_library(0);
  const int tries = std::max(1, options.port_tries);
  for (int i = 0; i < tries; ++i) {
    options_.port = options.port + i;
    const bool last = i + 1 == tries || options_.port == 65535;
    // A port taken by another run's viewer: the next one, unless this is the last try.
    if (!last && portInUse(options_.bind, options_.port)) continue;
    if (const std::string problem = checkBindable(options_.bind, options_.port); !problem.empty()) {
      throw ConfigError(problem);
    }
    context_ = start();
    if (context_ != nullptr || last) break;  // else taken between the check and the start
  }
  if (context_ == nullptr) {
    throw ConfigError("--bind " + options_.bind + " --port " + std::to_string(options_.port) +
                      ": the web server cannot listen there");
  }
  mg_set_websocket_handler(context_, "/ws", &WebServer::wsConnect, &WebServer::wsReady, &WebServer::wsData,
                           &WebServer::wsClose, this);
  sender_ = std::thread([this] { sendLoop(); });
}

mg_context* WebServer::start() {
  const std::string ports = options_.bind + ":" + std::to_string(options_.port);
  const char* config[] = {"listening_ports", ports.c_str(),
                          "document_root", options_.web_dir.c_str(),
                          "enable_directory_listing", "no",
                          "num_threads", "8",
                          "request_timeout_ms", "10000",
                          "enable_websocket_ping_pong", "yes",
                          "websocket_timeout_ms", "3600000",
                          "static_file_max_age", "0",
                          nullptr};
  mg_callbacks callbacks{};
  callbacks.log_message = [](const mg_connection*, const char* message) {
    spdlog::debug("http: {}", message);
    return 1;
  };
  return mg_start(&callbacks, this, config);
}

WebServer::~WebServer() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    quit_ = true;
  }
  wake_.notify_all();
  sender_.join();
  mg_stop(context_);
}

void WebServer::handle(const std::string& prefix, HttpHandler handler) {
  handlers_.emplace_back(prefix, std::move(handler));
  mg_set_request_handler(context_, prefix.c_str(), &WebServer::dispatch, this);
}

void WebServer::onClientMessage(ClientMessageHandler handler) { on_message_ = std::move(handler); }

int WebServer::dispatch(mg_connection* conn, void* self_ptr) {
  auto* self = static_cast<WebServer*>(self_ptr);
  const mg_request_info* info = mg_get_request_info(conn);
  const std::string path = info->local_uri != nullptr ? info->local_uri : "";
  const std::string query = info->query_string != nullptr ? info->query_string : "";
  HttpResponse response{404, "text/plain", "not found: " + path + "\n"};
  for (const auto& [prefix, handler] : self->handlers_) {
    if (path.rfind(prefix, 0) == 0) {
      try {
        response = handler(path, query);
      } catch (const std::exception& e) {
        response = {400, "text/plain", std::string(e.what()) + "\n"};
      }
      break;
    }
  }
  mg_printf(conn,
            "HTTP/1.1 %d %s\r\nContent-Type: %s\r\nContent-Length: %zu\r\nCache-Control: no-store\r\n"
            "Connection: close\r\n\r\n",
            response.status, mg_get_response_code_text(conn, response.status), response.content_type.c_str(),
            response.body.size());
  mg_write(conn, response.body.data(), response.body.size());
  return response.status;
}

int WebServer::wsConnect(const mg_connection* conn, void* self_ptr) {
  auto* self = static_cast<WebServer*>(self_ptr);
  auto client = std::make_shared<Client>();
  client->conn = const_cast<mg_connection*>(conn);
  std::lock_guard<std::mutex> lock(self->mutex_);
  self->clients_[conn] = client;
  return 0;  // accept
}

void WebServer::wsReady(mg_connection* conn, void* self_ptr) {
  auto* self = static_cast<WebServer*>(self_ptr);
  {
    std::lock_guard<std::mutex> lock(self->mutex_);
    const auto it = self->clients_.find(conn);
    if (it != self->clients_.end()) it->second->ready = true;
  }
  self->wake_.notify_all();
}

int WebServer::wsData(mg_connection* conn, int bits, char* data, std::size_t length, void* self_ptr) {
  auto* self = static_cast<WebServer*>(self_ptr);
  const int opcode = bits & 0x0f;
  if (opcode == MG_WEBSOCKET_OPCODE_CONNECTION_CLOSE) return 0;
  if (opcode == MG_WEBSOCKET_OPCODE_PING || opcode == MG_WEBSOCKET_OPCODE_PONG) return 1;
  const std::string text(data, length);
  const bool ok = opcode == MG_WEBSOCKET_OPCODE_TEXT && (bits & 0x80) != 0 && self->on_message_ &&
                  self->on_message_(text);
  if (ok) return 1;
  const mg_request_info* info = mg_get_request_info(conn);
  spdlog::warn("client {}:{} sent garbage ({} bytes, opcode {}); disconnected", info->remote_addr,
               info->remote_port, length, opcode);
  ++self->dropped_;
  return 0;  // closes the connection
}

void WebServer::wsClose(const mg_connection* conn, void* self_ptr) {
  auto* self = static_cast<WebServer*>(self_ptr);
  std::shared_ptr<Client> client;
  {
    std::lock_guard<std::mutex> lock(self->mutex_);
    const auto it = self->clients_.find(conn);
    if (it == self->clients_.end()) return;
    client = it->second;
    self->clients_.erase(it);
  }
  std::lock_guard<std::mutex> write_lock(client->write_mutex);
  client->closed = true;
}

void WebServer::publish(const std::string& channel, std::string text) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    latest_[channel] = std::make_shared<const std::string>(std::move(text));
    ++version_;
  }
  wake_.notify_all();
}

int WebServer::clientCount() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return static_cast<int>(clients_.size());
}

void WebServer::sendLoop() {
  std::uint64_t seen_version = ~std::uint64_t{0};
  std::size_t seen_ready = 0;
  for (;;) {
    std::vector<std::pair<std::shared_ptr<Client>, std::vector<std::shared_ptr<const std::string>>>> work;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      const auto readyCount = [&] {
        std::size_t ready = 0;
        for (const auto& entry : clients_) ready += entry.second->ready ? 1 : 0;
        return ready;
      };
      wake_.wait(lock, [&] { return quit_ || version_ != seen_version || readyCount() != seen_ready; });
      if (quit_) return;
      seen_version = version_;
      seen_ready = readyCount();
      for (auto& [conn, client] : clients_) {
        if (!client->ready) continue;
        std::vector<std::shared_ptr<const std::string>> messages;
        for (const auto& [channel, message] : latest_) {
          auto& sent = client->sent[channel];
          if (sent != message) messages.push_back(sent = message);
        }
        if (!messages.empty()) work.emplace_back(client, std::move(messages));
      }
    }
    // Outside the server's lock: a stuck client delays only the sender, never publish().
    std::uint64_t sent = 0;
    for (auto& [client, messages] : work) {
      std::lock_guard<std::mutex> write_lock(client->write_mutex);
      for (const auto& message : messages) {
        if (client->closed ||
            mg_websocket_write(client->conn, MG_WEBSOCKET_OPCODE_TEXT, message->data(), message->size()) <= 0) {
          break;
        }
        ++sent;
      }
    }
    sent_ += sent;
  }
}

std::string WebServer::url() const {
  std::string host = options_.bind;
  if (host == "0.0.0.0") {
    char name[256] = {};
    if (::gethostname(name, sizeof name - 1) == 0) host = name;
  }
  return "http://" + host + ":" + std::to_string(options_.port) + "/";
}

}  // namespace climbsim::viewer
