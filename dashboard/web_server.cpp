#include "dashboard/web_server.hpp"

#include <fmt/format.h>

#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/post.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>

#include <chrono>
#include <deque>
#include <filesystem>
#include <map>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <thread>
#include <vector>

namespace lcm_control::dashboard {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
using tcp = asio::ip::tcp;
using Clock = std::chrono::steady_clock;
using beast::error_code;

namespace {

// An open connection, HTTP or WebSocket, as the bounds see it (the server's thread only).
struct Conn {
  std::string address;
  Clock::time_point last_active = Clock::now();
  bool closed = false;
  virtual ~Conn() = default;
  virtual void shut() = 0;  // close the socket: its pending reads and writes end with an error
};

std::string content_type(const std::string& path) {
  static const std::map<std::string, std::string> types = {
      {".html", "text/html; charset=utf-8"}, {".js", "text/javascript; charset=utf-8"},
      {".mjs", "text/javascript; charset=utf-8"}, {".css", "text/css; charset=utf-8"},
      {".json", "application/json"}, {".map", "application/json"}, {".svg", "image/svg+xml"},
      {".png", "image/png"}, {".jpg", "image/jpeg"}, {".jpeg", "image/jpeg"}, {".ico", "image/x-icon"},
      {".urdf", "application/xml"}, {".xacro", "application/xml"}, {".xml", "application/xml"},
      {".dae", "model/vnd.collada+xml"}, {".stl", "model/stl"}, {".obj", "model/obj"}, {".txt", "text/plain"}};
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  const auto it = types.find(ext);
  return it == types.end() ? "application/octet-stream" : it->second;
}

}  // namespace

class WsSession;

struct WebServer::Impl {
  Impl(Handlers h, std::string root, bool loopback_only)
      : handlers(std::move(h)), web_root(std::move(root)), loopback_only(loopback_only) {}

  asio::io_context io{1};
  tcp::acceptor acceptor{io};
  Handlers handlers;
  const std::string web_root;
  const bool loopback_only;

  std::mutex mutex;  // guards what other threads reach: the browsers, the routes, the counters
  std::map<int, std::shared_ptr<WsSession>> browsers;
  std::map<std::string, Route> routes;
  int next_id = 1;
  int64_t dropped = 0, closed_for_room = 0;

  std::vector<std::weak_ptr<Conn>> open;  // the server's thread only
  std::thread thread;

  void accept();
  void make_room(const std::string& address);
  void track(const std::shared_ptr<Conn>& c) { open.push_back(c); }
  std::string route_file(const std::string& path, int& status);
};

// One browser's WebSocket: reads its messages (at most kMaxIncoming each) and writes its queue, one frame at a time.
class WsSession : public Conn, public std::enable_shared_from_this<WsSession> {
 public:
  WsSession(WebServer::Impl& server, tcp::socket socket) : server_(server), ws_(std::move(socket)) {}

  void start(http::request<http::string_body> req) {
    beast::get_lowest_layer(ws_).expires_never();
    websocket::stream_base::timeout t{};
    t.handshake_timeout = std::chrono::milliseconds(WebServer::kHeaderTimeoutMs);
    t.idle_timeout = websocket::stream_base::none();
    t.keep_alive_pings = false;
    ws_.set_option(t);
    ws_.read_message_max(WebServer::kMaxIncoming);
    ws_.async_accept(req, [self = shared_from_this()](error_code ec) { self->on_accept(ec); });
  }

  // With the server's mutex held; from any thread.
  bool enqueue(std::shared_ptr<const std::string> text) {
    if (closed_) return false;
    if (queue_.size() >= WebServer::kMaxQueued) {
      queue_.erase(writing_ ? queue_.begin() + 1 : queue_.begin());  // never the frame being written
      ++server_.dropped;
    }
    queue_.push_back(std::move(text));
    if (!writing_) {
      writing_ = true;
      asio::post(server_.io, [self = shared_from_this()] { self->write_next(); });
    }
    return true;
  }

  void shut() override {
    error_code ignored;
    beast::get_lowest_layer(ws_).socket().close(ignored);
  }

 private:
  void on_accept(error_code ec) {
    if (ec) return shut();
    {
      std::lock_guard<std::mutex> lock(server_.mutex);
      id_ = server_.next_id++;
      server_.browsers[id_] = shared_from_this();
    }
    if (server_.handlers.opened) server_.handlers.opened(id_);
    read();
  }

  void read() {
    ws_.async_read(buffer_, [self = shared_from_this()](error_code ec, size_t) { self->on_read(ec); });
  }

  void on_read(error_code ec) {
    if (ec) return finish();
    last_active = Clock::now();
    if (ws_.got_text()) {
      const std::string text = beast::buffers_to_string(buffer_.data());
      buffer_.consume(buffer_.size());
      if (server_.handlers.text) server_.handlers.text(id_, text);
    } else {
      buffer_.consume(buffer_.size());  // the page sends text only
    }
    read();
  }

  void write_next() {
    std::shared_ptr<const std::string> text;
    {
      std::lock_guard<std::mutex> lock(server_.mutex);
      if (closed_ || queue_.empty()) {
        writing_ = false;
        return;
      }
      text = queue_.front();
    }
    ws_.text(true);
    ws_.async_write(asio::buffer(*text), [self = shared_from_this(), text](error_code ec, size_t) {
      {
        std::lock_guard<std::mutex> lock(self->server_.mutex);
        if (!self->queue_.empty()) self->queue_.pop_front();
      }
      if (ec) return self->finish();
      self->write_next();
    });
  }

  void finish() {
    {
      std::lock_guard<std::mutex> lock(server_.mutex);
      if (closed_) return;
      closed_ = true;
      queue_.clear();
      server_.browsers.erase(id_);
    }
    closed = true;
    shut();
    if (server_.handlers.closed) server_.handlers.closed(id_);
  }

  WebServer::Impl& server_;
  websocket::stream<beast::tcp_stream> ws_;
  beast::flat_buffer buffer_;
  int id_ = 0;
  std::deque<std::shared_ptr<const std::string>> queue_;  // guarded by the server's mutex, as are the two below
  bool writing_ = false, closed_ = false;
};

// One HTTP connection: requests read with a deadline and a size bound, answered with a file or an error, or handed to
// a WebSocket session on /ws.
class HttpSession : public Conn, public std::enable_shared_from_this<HttpSession> {
 public:
  HttpSession(WebServer::Impl& server, tcp::socket socket) : server_(server), stream_(std::move(socket)) {}

  void read() {
    parser_.emplace();
    parser_->header_limit(WebServer::kMaxHeaderBytes);
    parser_->body_limit(WebServer::kMaxHeaderBytes);
    stream_.expires_after(std::chrono::milliseconds(WebServer::kHeaderTimeoutMs));
    http::async_read(stream_, buffer_, *parser_, [self = shared_from_this()](error_code ec, size_t) {
      self->on_read(ec);
    });
  }

  void shut() override {
    error_code ignored;
    stream_.socket().close(ignored);
  }

 private:
  void on_read(error_code ec) {
    if (ec == http::error::header_limit || ec == http::error::body_limit)
      return error(431, "the request's headers are too large", false);
    if (ec) return end();
    last_active = Clock::now();
    http::request<http::string_body> req = parser_->release();
    version_ = req.version();
    keep_alive_ = req.keep_alive();
    const std::string host(req[http::field::host]), origin(req[http::field::origin]);
    if (const std::string why = WebServer::refuse_reason(host, origin, server_.loopback_only); !why.empty())
      return error(403, why, false);
    std::string path;
    if (!WebServer::decode_path(std::string(req.target()), path)) return error(400, "a bad %-escape in the path", false);
    if (websocket::is_upgrade(req)) {
      if (path != "/ws") return error(404, "not found", false);
      stream_.expires_never();
      auto ws = std::make_shared<WsSession>(server_, stream_.release_socket());
      ws->address = address;
      closed = true;  // the WebSocket takes this connection's place
      server_.track(ws);
      ws->start(std::move(req));
      return;
    }
    if (req.method() != http::verb::get && req.method() != http::verb::head)
      return error(405, "only GET", false);
    int status = 404;
    std::string file;
    try {
      file = server_.route_file(path, status);
    } catch (const std::exception& e) {
      return error(500, e.what(), keep_alive_);
    }
    if (file.empty()) return error(status, "not found", keep_alive_);
    http::file_body::value_type body;
    body.open(file.c_str(), beast::file_mode::scan, ec);
    if (ec) return error(404, "not found", keep_alive_);
    const auto size = body.size();
    if (req.method() == http::verb::head) {
      auto res = std::make_shared<http::response<http::empty_body>>(http::status::ok, version_);
      res->set(http::field::content_type, content_type(file));
      res->content_length(size);
      res->keep_alive(keep_alive_);
      return write(res);
    }
    auto res = std::make_shared<http::response<http::file_body>>(
        std::piecewise_construct, std::make_tuple(std::move(body)), std::make_tuple(http::status::ok, version_));
    res->set(http::field::content_type, content_type(file));
    res->set(http::field::cache_control, "no-cache");
    res->content_length(size);
    res->keep_alive(keep_alive_);
    write(res);
  }

  void error(int status, const std::string& why, bool keep_alive) {
    auto res = std::make_shared<http::response<http::string_body>>(http::int_to_status(unsigned(status)), version_);
    res->set(http::field::content_type, "text/plain; charset=utf-8");
    res->body() = fmt::format("Error {}: {}\n", status, why);
    res->prepare_payload();
    res->keep_alive(keep_alive);
    write(res);
  }

  template <class Response>
  void write(std::shared_ptr<Response> res) {
    stream_.expires_after(std::chrono::seconds(60));  // a mesh to a client that reads slowly, at the most
    http::async_write(stream_, *res, [self = shared_from_this(), res](error_code ec, size_t) {
      if (ec || !res->keep_alive()) return self->end();
      self->read();
    });
  }

  void end() {
    error_code ignored;
    stream_.socket().shutdown(tcp::socket::shutdown_send, ignored);
    closed = true;
    shut();
  }

  WebServer::Impl& server_;
  beast::tcp_stream stream_;
  beast::flat_buffer buffer_;
  std::optional<http::request_parser<http::string_body>> parser_;
  unsigned version_ = 11;
  bool keep_alive_ = false;
};

void WebServer::Impl::accept() {
  acceptor.async_accept([this](error_code ec, tcp::socket socket) {
    if (!ec) {
      error_code aec;
      const auto remote = socket.remote_endpoint(aec);
      const std::string addr = aec ? std::string() : remote.address().to_string();
      make_room(addr);
      auto s = std::make_shared<HttpSession>(*this, std::move(socket));
      s->address = addr;
      track(s);
      s->read();
    }
    if (acceptor.is_open()) accept();
  });
}

void WebServer::Impl::make_room(const std::string& address) {
  std::vector<std::shared_ptr<Conn>> live;
  std::vector<std::weak_ptr<Conn>> kept;
  for (const auto& w : open)
    if (auto c = w.lock(); c && !c->closed) {
      live.push_back(c);
      kept.push_back(w);
    }
  open.swap(kept);
  auto close_idlest = [&](bool same_address) {
    std::shared_ptr<Conn> idlest;
    for (const auto& c : live)
      if (!c->closed && (!same_address || c->address == address) &&
          (!idlest || c->last_active < idlest->last_active))
        idlest = c;
    if (!idlest) return;
    idlest->closed = true;
    idlest->shut();
    std::lock_guard<std::mutex> lock(mutex);
    ++closed_for_room;
  };
  auto count = [&](bool same_address) {
    size_t n = 0;
    for (const auto& c : live) n += !c->closed && (!same_address || c->address == address);
    return n;
  };
  while (count(true) >= kMaxPerClient) close_idlest(true);
  while (count(false) >= kMaxConnections) close_idlest(false);
}

std::string WebServer::Impl::route_file(const std::string& path, int& status) {
  Route route;
  std::string rest;
  {
    std::lock_guard<std::mutex> lock(mutex);
    size_t best = 0;
    for (const auto& [prefix, r] : routes)
      if (path.rfind(prefix, 0) == 0 && prefix.size() > best) {
        best = prefix.size();
        route = r;
        rest = path.substr(prefix.size());
      }
  }
  status = 404;
  if (route) return route(rest);
  std::string file = path.substr(1);
  if (file.empty() || file.back() == '/') file += "index.html";
  return file_under(web_root, file);
}

WebServer::WebServer(const std::string& bind, int port, const std::string& web_root, Handlers handlers)
    : impl_(std::make_unique<Impl>(std::move(handlers), web_root, loopback(bind))) {
  const std::string listen = fmt::format("{}:{}", bind, port);
  auto fail = [&] {
    return std::runtime_error(fmt::format(
        "cannot serve on {}: the port is in use or {} is not an address of this computer; pick another with "
        "--port (0 lets the system choose) or --bind",
        listen, bind));
  };
  if (port < 0 || port > 65535) throw fail();
  error_code ec;
  const auto address = asio::ip::make_address(bind == "localhost" ? "127.0.0.1" : bind, ec);
  if (ec) throw fail();
  const tcp::endpoint at(address, uint16_t(port));
  auto& a = impl_->acceptor;
  a.open(at.protocol(), ec);
  if (!ec) a.set_option(asio::socket_base::reuse_address(true), ec);
  if (!ec) a.bind(at, ec);
  if (!ec) a.listen(asio::socket_base::max_listen_connections, ec);
  if (ec) throw fail();
  port_ = a.local_endpoint().port();
  impl_->accept();
  impl_->thread = std::thread([this] { impl_->io.run(); });
}

WebServer::~WebServer() {
  impl_->io.stop();
  impl_->thread.join();
  std::lock_guard<std::mutex> lock(impl_->mutex);
  impl_->browsers.clear();
}

void WebServer::route(const std::string& prefix, Route route) {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  impl_->routes[prefix] = std::move(route);
}

bool WebServer::send(int id, const std::string& text) {
  auto shared = std::make_shared<const std::string>(text);
  std::lock_guard<std::mutex> lock(impl_->mutex);
  const auto it = impl_->browsers.find(id);
  return it != impl_->browsers.end() && it->second->enqueue(std::move(shared));
}

void WebServer::broadcast(const std::string& text) {
  auto shared = std::make_shared<const std::string>(text);
  std::lock_guard<std::mutex> lock(impl_->mutex);
  for (auto& [id, b] : impl_->browsers) b->enqueue(shared);
}

size_t WebServer::connections() {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  return impl_->browsers.size();
}

int64_t WebServer::dropped() {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  return impl_->dropped;
}

int64_t WebServer::closed_for_room() {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  return impl_->closed_for_room;
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

bool WebServer::decode_path(const std::string& target, std::string& path) {
  path.clear();
  const std::string raw = target.substr(0, target.find_first_of("?#"));
  if (raw.empty() || raw.front() != '/') return false;
  auto hex = [](char c) {
    return c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : c >= 'A' && c <= 'F' ? c - 'A' + 10 : -1;
  };
  for (size_t i = 0; i < raw.size(); ++i) {
    char c = raw[i];
    if (c == '%') {
      if (i + 2 >= raw.size()) return false;
      const int hi = hex(raw[i + 1]), lo = hex(raw[i + 2]);
      if (hi < 0 || lo < 0) return false;
      c = char(hi * 16 + lo);
      i += 2;
    }
    if (c == '\0') return false;
    path += c;
  }
  return true;
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

}  // namespace lcm_control::dashboard
