#include "dashboard/web_server.hpp"

#include <civetweb.h>
#include <fmt/format.h>

#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <vector>

namespace lcm_control::dashboard {
namespace {

// civetweb is started once per process (mg_init_library); several servers share it.
struct Library {
  Library() { mg_init_library(0); }
  ~Library() { mg_exit_library(); }
};

}  // namespace

WebServer::WebServer(const std::string& bind, int port, const std::string& web_root, Handlers handlers)
    : handlers_(std::move(handlers)) {
  static Library library;
  const std::string listen = fmt::format("{}:{}", bind, port);
  const char* options[] = {"listening_ports", listen.c_str(), "document_root", web_root.c_str(),
                           "num_threads", "16", "enable_directory_listing", "no",
                           // a write to a browser that stops reading gives up after this long (only its own writer
                           // thread waits)
                           "request_timeout_ms", "5000", "websocket_timeout_ms", "3600000", nullptr};
  loopback_only_ = loopback(bind);
  mg_callbacks callbacks{};
  callbacks.log_message = [](const mg_connection*, const char*) { return 1; };  // errors are reported below
  callbacks.begin_request = &WebServer::on_request;
  ctx_ = mg_start(&callbacks, this, options);
  if (!ctx_)
    throw std::runtime_error(fmt::format(
        "cannot serve on {}: the port is in use or {} is not an address of this computer; pick another with "
        "--port (0 lets the system choose) or --bind",
        listen, bind));
  mg_server_port ports[4]{};
  const int n = mg_get_server_ports(ctx_, 4, ports);
  port_ = n > 0 ? ports[0].port : port;
  mg_set_websocket_handler(ctx_, "/ws", nullptr, &WebServer::on_ready, &WebServer::on_data,
                           &WebServer::on_close, this);
}

WebServer::~WebServer() {
  if (ctx_) mg_stop(ctx_);
}

void WebServer::route(const std::string& prefix, Route route) {
  auto& entry = routes_[prefix];
  entry = RouteEntry{prefix, std::move(route)};
  mg_set_request_handler(ctx_, prefix.c_str(), &WebServer::on_route, &entry);
}

std::string WebServer::refuse_reason(const std::string& host, const std::string& origin, bool loopback_only) {
  if (host.empty()) return "no Host header";
  if (loopback_only) {
    std::string name = host;
    if (name.front() == '[') {
      name = name.substr(0, name.find(']') + 1);
    } else if (const size_t colon = name.rfind(':'); colon != std::string::npos) {
      name.resize(colon);
    }
    if (name != "127.0.0.1" && name != "localhost" && name != "[::1]")
      return fmt::format("the dashboard serves this computer only: open it as http://127.0.0.1:PORT/, not through the "
                         "name '{}'",
                         name);
  }
  if (!origin.empty() && origin != "http://" + host && origin != "https://" + host)
    return fmt::format("a page from {} may not use the dashboard at {}: only its own page may", origin, host);
  return "";
}

int WebServer::on_request(mg_connection* conn) {
  const auto* self = static_cast<const WebServer*>(mg_get_user_data(mg_get_context(conn)));
  const char* host = mg_get_header(conn, "Host");
  const char* origin = mg_get_header(conn, "Origin");
  const std::string why = refuse_reason(host ? host : "", origin ? origin : "", self->loopback_only_);
  if (why.empty()) return 0;
  mg_send_http_error(conn, 403, "%s", why.c_str());
  return 403;
}

int WebServer::on_route(mg_connection* conn, void* cbdata) {
  const auto* entry = static_cast<const RouteEntry*>(cbdata);
  const mg_request_info* info = mg_get_request_info(conn);
  if (std::strcmp(info->request_method, "GET") != 0) {
    mg_send_http_error(conn, 405, "%s", "only GET");
    return 405;
  }
  const std::string uri = info->local_uri ? info->local_uri : "";
  const std::string rest = uri.size() >= entry->prefix.size() ? uri.substr(entry->prefix.size()) : "";
  std::string file;
  try {
    file = entry->route(rest);
  } catch (const std::exception& e) {
    mg_send_http_error(conn, 500, "%s", e.what());
    return 500;
  }
  if (file.empty()) {
    mg_send_http_error(conn, 404, "%s", "not found");
    return 404;
  }
  mg_send_file(conn, file.c_str());
  return 200;
}

bool WebServer::loopback(const std::string& bind) { return bind == "127.0.0.1" || bind == "localhost" || bind == "::1"; }

std::string WebServer::file_under(const std::string& root, const std::string& rest) {
  namespace fs = std::filesystem;
  if (root.empty() || rest.empty() || rest.front() == '/') return "";
  std::error_code ec;
  const fs::path r = fs::canonical(root, ec);
  if (ec) return "";
  const fs::path p = fs::weakly_canonical(r / rest, ec);  // resolves "..", and links that lead out of root
  if (ec || p.string().rfind(r.string() + "/", 0) != 0) return "";
  return fs::is_regular_file(p, ec) ? p.string() : "";
}

void WebServer::on_ready(mg_connection* conn, void* cbdata) {
  auto* self = static_cast<WebServer*>(cbdata);
  int id = 0;
  {
    std::lock_guard<std::mutex> lock(self->mutex_);
    id = self->next_id_++;
    auto b = std::make_unique<Browser>();
    b->conn = conn;
    b->writer = std::thread(&WebServer::write_loop, self, b.get());
    self->conns_[id] = std::move(b);
    self->ids_[conn] = id;
  }
  if (self->handlers_.opened) self->handlers_.opened(id);
}

void WebServer::write_loop(Browser* b) {
  std::unique_lock<std::mutex> lock(mutex_);
  while (true) {
    b->cv.wait(lock, [&] { return b->closing || !b->queue.empty(); });
    if (b->closing) return;
    std::string text = std::move(b->queue.front());
    b->queue.pop_front();
    lock.unlock();
    // Blocks while the browser does not read; only this browser's thread waits.
    mg_websocket_write(b->conn, MG_WEBSOCKET_OPCODE_TEXT, text.data(), text.size());
    lock.lock();
  }
}

bool WebServer::enqueue(Browser& b, const std::string& text) {
  if (b.closing) return false;
  if (b.queue.size() >= kMaxQueued) {
    b.queue.pop_front();
    ++dropped_;
  }
  b.queue.push_back(text);
  b.cv.notify_one();
  return true;
}

int WebServer::on_data(mg_connection* conn, int bits, char* data, size_t len, void* cbdata) {
  auto* self = static_cast<WebServer*>(cbdata);
  const int opcode = bits & 0x0f;
  const bool fin = (bits & 0x80) != 0;
  if (opcode == MG_WEBSOCKET_OPCODE_CONNECTION_CLOSE) return 0;
  if (opcode == MG_WEBSOCKET_OPCODE_PING || opcode == MG_WEBSOCKET_OPCODE_PONG) return 1;
  int id = 0;
  std::string text;
  {
    std::lock_guard<std::mutex> lock(self->mutex_);
    const auto it = self->ids_.find(conn);
    if (it == self->ids_.end()) return 0;
    id = it->second;
    std::string& partial = self->partial_[id];
    if (opcode != MG_WEBSOCKET_OPCODE_CONTINUATION) partial.clear();
    if (partial.size() + len > kMaxIncoming) return 0;
    partial.append(data, len);
    if (!fin) return 1;
    text.swap(partial);
  }
  if (opcode == MG_WEBSOCKET_OPCODE_BINARY) return 1;  // the page sends text only
  if (self->handlers_.text) self->handlers_.text(id, text);
  return 1;
}

void WebServer::on_close(const mg_connection* conn, void* cbdata) {
  auto* self = static_cast<WebServer*>(cbdata);
  int id = 0;
  std::unique_ptr<Browser> gone;
  {
    std::lock_guard<std::mutex> lock(self->mutex_);
    const auto it = self->ids_.find(conn);
    if (it == self->ids_.end()) return;
    id = it->second;
    self->ids_.erase(it);
    gone = std::move(self->conns_[id]);
    self->conns_.erase(id);
    self->partial_.erase(id);
    gone->closing = true;
    gone->cv.notify_one();
  }
  // civetweb frees the connection after this returns: its writer must be done with it first.
  gone->writer.join();
  if (self->handlers_.closed) self->handlers_.closed(id);
}

bool WebServer::send(int id, const std::string& text) {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto it = conns_.find(id);
  return it != conns_.end() && enqueue(*it->second, text);
}

void WebServer::broadcast(const std::string& text) {
  std::lock_guard<std::mutex> lock(mutex_);
  for (auto& [id, b] : conns_) enqueue(*b, text);
}

size_t WebServer::connections() {
  std::lock_guard<std::mutex> lock(mutex_);
  return conns_.size();
}

int64_t WebServer::dropped() {
  std::lock_guard<std::mutex> lock(mutex_);
  return dropped_;
}

}  // namespace lcm_control::dashboard
