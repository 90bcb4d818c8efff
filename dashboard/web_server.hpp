// The dashboard's HTTP and WebSocket server (Boost.Beast on one thread of its own): the page's files from a folder, a
// few routes the program adds (the URDF, the robot's meshes), and the browsers' WebSocket connections on /ws, each
// with a number. Whatever a client sends, it holds no thread and no more memory than the limits below.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

namespace lcm_control::dashboard {

class WebServer {
 public:
  struct Handlers {  // called on the server's thread: hand the work on, do not block
    std::function<void(int id)> opened;                           // a browser connected (send it a hello)
    std::function<void(int id, const std::string& text)> text;    // one text message from browser id
    std::function<void(int id)> closed;
  };
  // A route's answer for the rest of the path after its prefix: the file to send, "" for 404.
  using Route = std::function<std::string(const std::string& rest)>;

  // Serves `web_root` and /ws on bind:port (port 0: one the system picks). Throws std::runtime_error naming the
  // address and what to do when it cannot listen (in use, not an address of this computer).
  WebServer(const std::string& bind, int port, const std::string& web_root, Handlers handlers);
  ~WebServer();
  WebServer(const WebServer&) = delete;
  WebServer& operator=(const WebServer&) = delete;

  // GET PREFIX<rest> answered by route(rest) (the longest prefix that matches).
  void route(const std::string& prefix, Route route);

  int port() const { return port_; }
  // Text to one browser / to all, queued: a browser that stops reading holds up neither the caller nor the other
  // browsers. A browser more than kMaxQueued frames behind loses its oldest (counted in dropped()). send() is false
  // when the browser is gone.
  bool send(int id, const std::string& text);
  void broadcast(const std::string& text);
  size_t connections();  // WebSocket browsers
  int64_t dropped();
  int64_t closed_for_room();  // connections closed (the idle longest first) to make room for a new one

  static constexpr size_t kMaxQueued = 1000;
  // Incoming WebSocket messages larger than this are refused from their frame's header, before any of it is read
  // (the connection is closed with status 1009).
  static constexpr size_t kMaxIncoming = 64 * 1024;
  // A request's line and headers: at most this many bytes, within this long (a client that trickles them is closed).
  static constexpr size_t kMaxHeaderBytes = 16 * 1024;
  static constexpr int kHeaderTimeoutMs = 1000;
  // Open connections (HTTP and WebSocket) from one client address, and in all. A new one at either bound closes the
  // one that has been idle longest (of that address, or of all), so a new client is always served.
  static constexpr size_t kMaxPerClient = 32;
  static constexpr size_t kMaxConnections = 128;

  // Whether `bind` is this computer's loopback (then only the loopback names are answered, see refuse_reason).
  static bool loopback(const std::string& bind);

  // root/rest when that names a regular file inside root ("" for "..", an absolute path, a link out of root, a
  // folder or nothing): what a route may send for a path a browser gave.
  static std::string file_under(const std::string& root, const std::string& rest);

  // Why a request with these Host and Origin headers is refused, "" to serve it. Any web page the user's browser
  // opens could otherwise command the robot: a WebSocket may connect across origins, and a name the attacker
  // controls may resolve to 127.0.0.1 (DNS rebinding). So a request that comes with an Origin must come from a page
  // this server served (Origin = http://Host), and a server on loopback answers only to its loopback names.
  static std::string refuse_reason(const std::string& host, const std::string& origin, bool loopback_only);

  // The path of a request target (before any '?') with its %XX escapes decoded into `path`; false for a bad escape
  // or a NUL.
  static bool decode_path(const std::string& target, std::string& path);

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
  int port_ = 0;
};

}  // namespace lcm_control::dashboard
