// The dashboard's HTTP and WebSocket server (civetweb): the page's files from a folder, a few routes the program
// adds (the URDF, the robot's meshes), and the browsers' WebSocket connections on /ws, each with a number.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

struct mg_context;
struct mg_connection;

namespace lcm_control::dashboard {

class WebServer {
 public:
  struct Handlers {
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

  // GET PREFIX<rest> answered by route(rest); add before browsers connect.
  void route(const std::string& prefix, Route route);

  int port() const { return port_; }
  // Text to one browser / to all, queued: each browser has a writer thread of its own, so one that stops reading
  // holds up neither the caller nor the other browsers. A browser more than kMaxQueued frames behind loses its
  // oldest (counted in dropped()). send() is false when the browser is gone.
  bool send(int id, const std::string& text);
  void broadcast(const std::string& text);
  size_t connections();
  int64_t dropped();

  static constexpr size_t kMaxQueued = 1000;

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

  // Incoming WebSocket messages larger than this are refused (the connection is closed).
  static constexpr size_t kMaxIncoming = 64 * 1024;

 private:
  static void on_ready(mg_connection*, void*);
  static int on_data(mg_connection*, int bits, char* data, size_t len, void*);
  static void on_close(const mg_connection*, void*);
  static int on_route(mg_connection*, void*);
  static int on_request(mg_connection*);

  mg_context* ctx_ = nullptr;
  Handlers handlers_;
  int port_ = 0;
  bool loopback_only_ = true;
  // One browser: its connection, what waits to be written, and the thread that writes it.
  struct Browser {
    mg_connection* conn = nullptr;
    std::deque<std::string> queue;
    std::condition_variable cv;
    bool closing = false;
    std::thread writer;
  };
  void write_loop(Browser* b);
  bool enqueue(Browser& b, const std::string& text);  // with mutex_ held

  std::mutex mutex_;
  std::map<int, std::unique_ptr<Browser>> conns_;
  int64_t dropped_ = 0;
  std::map<const mg_connection*, int> ids_;
  std::map<int, std::string> partial_;  // a fragmented message until its last frame
  int next_id_ = 1;
  struct RouteEntry {
    std::string prefix;
    Route route;
  };
  std::map<std::string, RouteEntry> routes_;
};

}  // namespace lcm_control::dashboard
