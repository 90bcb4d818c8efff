#include "controller_manager/command_sources.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include <array>
#include <cmath>

#include "bus/digest.hpp"
#include "controller_manager/loop.hpp"

namespace lcm_control::cm {

// The ticks published on the channel and not yet received back from the bus, by the hash of their bytes (a tick
// is published once; the oldest are forgotten when more than kSize wait, as when their echoes were lost).
struct CommandSources::Echoes {
  static constexpr int kSize = 1024;  // a second of ticks at 1 kHz: more than the shared bus ever lags the loop
  std::array<size_t, kSize> hash{};
  int first = 0, count = 0;
  void sent(size_t h) {
    if (count == kSize) first = (first + 1) % kSize, --count;
    hash[static_cast<size_t>((first + count++) % kSize)] = h;
  }
  // True when `h` is one of ours: it and any older ones (lost on the way) are taken off.
  bool received(size_t h) {
    for (int k = 0; k < count; ++k)
      if (hash[static_cast<size_t>((first + k) % kSize)] == h) {
        first = (first + k + 1) % kSize;
        count -= k + 1;
        return true;
      }
    return false;
  }
};

struct CommandSources::Source {
  std::string controller, client, summary, channel;
  Endpoints* endpoints = nullptr;  // the controller's, whose channel this source owns (diverted); null once given back
  Echoes echoes;
  int64_t ignored = 0;  // messages from the bus on the channel that were not this source's echoes
  int64_t request_id = 0;
  ControllerSlot* slot = nullptr;  // null once ended
  std::unique_ptr<Expressions> exprs;
  std::vector<double> values;
  bool array = false;
  float64_t one{};
  float64_array_t many{};
  const CommandInput* input = nullptr;  // the controller's: the values go to it as numbers
  std::vector<uint8_t> bytes;           // the tick as published on the channel (its hash marks the echo)
  double rate = 0, duration = 0;
  int64_t count = 0;
  bool started = false, fresh = false;
  int64_t start_us = 0, last_us = 0, next = 0, ticks = 0, restarts = 0;
  // Set when it ends (on the loop path: constants only), announced by poll().
  const char* end = nullptr;
  int64_t end_i = 0;
  double end_t = 0;
  int bad_expr = -1;
};

CommandSources::CommandSources(Loop& loop, Bus& bus)
    : loop_(loop),
      bus_(bus),
      endpoints_(bus, Endpoints::On::Shared),
      response_pub_(endpoints_.publisher<cm_response_t>(bus.channel(channels::kCmResponse))) {
  const std::string channel = bus.channel(channels::kCmCommandSource);
  endpoints_.subscribe<command_source_t>(
      channel,
      [this](const command_source_t& r) {
        const cm_response_t* given = nullptr;
        if (ledger_.seen(r.request_id, &given) == AnswerLedger<cm_response_t>::Seen::Answered) {
          response_pub_.publish(*given);
          return;
        }
        answer(r.request_id, handle(r));
      },
      [this](const std::string& why) {
        const Reply reply{false, "malformed command source request: " + why + "; dropped (answered as -1)"};
        log_.warn(reply.message);
        answer(-1, reply);
      });
}

CommandSources::~CommandSources() = default;

void CommandSources::answer(int64_t request_id, const Reply& reply) {
  cm_response_t m{};  // every field zero: a field added to the type is never sent uninitialised
  m.utime = wall_us();
  m.request_id = request_id;
  m.op = cm_response_t::OP_COMMAND_SOURCE;
  m.ok = reply.ok;
  m.message = reply.message;
  m.num_controllers = 0;
  m.num_types = 0;
  m.hardware_age_us = -1;
  response_pub_.publish(m);
  ledger_.answered(m);
}

Reply CommandSources::handle(const command_source_t& r) {
  auto refuse = [&](const std::string& why) {
    Reply reply{false, fmt::format("command source for '{}' refused: {}", r.controller, why)};
    log_.warn(fmt::format("request {}{}: {}", r.request_id, r.client.empty() ? "" : " from " + clip(r.client), reply.message));
    return reply;
  };
  if (r.controller.empty()) return refuse("no controller named");
  if (r.remove) {
    for (auto& s : sources_)
      if (s->controller == r.controller && !s->end) {
        give_back(*s);
        s->end = "removed";
        s->slot = nullptr;
        const Reply reply{true, fmt::format("command source for '{}' removed after {} tick(s)", r.controller,
                                            s->ticks)};
        log_.info(fmt::format("request {}{}: {}", r.request_id, r.client.empty() ? "" : " from " + clip(r.client), reply.message));
        return reply;
      }
    return refuse("it has no command source to remove");
  }
  ControllerSlot* slot = nullptr;
  std::vector<std::string> loaded;
  for (auto& s : loop_.slots()) {
    loaded.push_back(s->name);
    if (s->name == r.controller) slot = s.get();
  }
  if (!slot)
    return refuse(fmt::format("it is not loaded (loaded: {})", loaded.empty() ? "none" : fmt::format("{}", fmt::join(loaded, ", "))));
  if (r.num_expressions != static_cast<int32_t>(r.expressions.size()) || r.expressions.empty())
    return refuse("no expression given");
  if (!std::isfinite(r.rate_hz) || r.rate_hz < 0) return refuse(fmt::format("rate_hz {} is not >= 0", r.rate_hz));
  if (!std::isfinite(r.duration_s) || r.duration_s < 0)
    return refuse(fmt::format("duration_s {} is not >= 0", r.duration_s));
  if (r.count < 0) return refuse(fmt::format("count {} is not >= 0", r.count));
  const std::string command_channel = bus_.channel(r.controller + "/command");
  const CommandInput* input = slot->controller->command_input();
  if (!input)
    return refuse(fmt::format("{} takes no float64_t / float64_array_t commands on '{}'", slot->type,
                              command_channel));
  const bool group = input->array;
  if (group && r.expressions.size() != input->width)
    return refuse(fmt::format("{} expression(s) for {} joints ({} takes one value per joint)", r.expressions.size(),
                              input->width, slot->type));
  if (!group && r.expressions.size() != 1)
    return refuse(fmt::format("{} expressions, but {} takes one value (float64_t)", r.expressions.size(), slot->type));
  auto src = std::make_unique<Source>();
  src->channel = command_channel;
  try {
    src->exprs = std::make_unique<Expressions>(r.expressions);
  } catch (const ExpressionError& e) {
    return refuse(e.what());
  }
  src->controller = r.controller;
  src->client = r.client;
  src->request_id = r.request_id;
  src->slot = slot;
  src->array = group;
  src->values.assign(r.expressions.size(), 0.0);
  src->many.size = static_cast<int32_t>(r.expressions.size());
  src->many.data.assign(r.expressions.size(), 0.0);
  src->bytes.resize(static_cast<size_t>(group ? src->many.getEncodedSize() : src->one.getEncodedSize()));
  src->input = input;
  src->rate = r.rate_hz;
  src->count = r.count;
  src->duration = r.duration_s;

  std::string replaced;
  for (auto& s : sources_) {
    if (s->controller != r.controller) continue;
    if (s->endpoints) {  // the new source takes the channel over, with the echoes still on their way
      src->echoes = s->echoes;
      s->endpoints = nullptr;
    }
    if (!s->end) {
      s->end = "replaced";
      s->slot = nullptr;
      replaced = fmt::format("; replaced the previous one (request {}, {} tick(s))", s->request_id, s->ticks);
    }
  }
  Source* owner = src.get();
  src->endpoints = slot->endpoints.get();
  src->endpoints->divert(command_channel, [this, owner](const lcm::ReceiveBuffer& rb) { from_bus(*owner, rb); });
  std::vector<std::string> limits;
  if (r.count > 0) limits.push_back(fmt::format("{} tick(s)", r.count));
  if (r.duration_s > 0) limits.push_back(fmt::format("{:g} s", r.duration_s));
  src->summary = fmt::format("[{}] {} on hardware time{}", fmt::join(r.expressions, ", "),
                             r.rate_hz > 0 ? fmt::format("at {:g} Hz", r.rate_hz) : std::string("every control step"),
                             limits.empty() ? "" : fmt::format(", for {}", fmt::join(limits, " or ")));
  const Reply reply{true, fmt::format("command source for '{}': {}; tick 0 at the {} cycle in which it runs{}",
                                      r.controller, src->summary, loop_.has_state() ? "next" : "first", replaced)};
  log_.info(fmt::format("request {}{}: {}", r.request_id, r.client.empty() ? "" : " from " + clip(r.client), reply.message));
  sources_.push_back(std::move(src));
  return reply;
}

void CommandSources::before_update(const Time& now) {
  for (auto& sp : sources_) {
    Source& s = *sp;
    if (s.end || !s.slot || !s.slot->running) continue;
    if (s.slot->async && s.slot->async->busy()) continue;  // its update is running: the tick waits for a cycle after
    if (!s.started || now.utime < s.last_us) {
      if (s.started) ++s.restarts;
      s.started = true;
      s.start_us = now.utime;
      s.next = 0;
    }
    s.last_us = now.utime;
    const double elapsed_us = static_cast<double>(now.utime - s.start_us);
    int64_t j = s.next;
    if (s.rate > 0) {
      j = static_cast<int64_t>(std::floor(elapsed_us * s.rate / 1e6 + 1e-9));
      if (j < s.next) continue;
    }
    const double t = s.rate > 0 ? static_cast<double>(j) / s.rate : elapsed_us * 1e-6;
    if ((s.count > 0 && j >= s.count) || (s.duration > 0 && t >= s.duration - 1e-9)) {
      s.end = s.count > 0 && j >= s.count ? "count reached" : "duration reached";
      s.end_i = j;
      s.end_t = t;
      continue;
    }
    const int bad = s.exprs->eval(j, t, s.values.data());
    if (bad >= 0) {
      s.end = "an expression is not finite";
      s.bad_expr = bad;
      s.end_i = j;
      s.end_t = t;
      continue;
    }
    const int64_t utime = s.rate > 0 ? s.start_us + std::llround(static_cast<double>(j) * 1e6 / s.rate) : now.utime;
    s.input->set(s.values.data());
    if (s.array) {
      s.many.utime = utime;
      for (size_t k = 0; k < s.values.size(); ++k) s.many.data[k] = s.values[k];
    } else {
      s.one.utime = utime;
      s.one.data = s.values[0];
    }
    s.fresh = true;
    s.next = j + 1;
    ++s.ticks;
    if (s.count > 0 && s.next >= s.count) {
      s.end = "count reached";
      s.end_i = j;
      s.end_t = t;
    }
  }
}

void CommandSources::after_cycle() {
  for (auto& sp : sources_) {
    Source& s = *sp;
    if (!s.fresh) continue;
    s.fresh = false;
    const int n = s.array ? s.many.encode(s.bytes.data(), 0, static_cast<int>(s.bytes.size()))
                          : s.one.encode(s.bytes.data(), 0, static_cast<int>(s.bytes.size()));
    if (n <= 0) continue;
    s.echoes.sent(message_digest(s.bytes.data(), static_cast<size_t>(n)));
    endpoints_.lcm().publish(s.channel, s.bytes.data(), static_cast<unsigned>(n));
  }
}

void CommandSources::poll() {
  for (size_t k = 0; k < sources_.size();) {
    Source& s = *sources_[k];
    if (!s.end || s.fresh) {
      ++k;
      continue;
    }
    std::string why = s.end;
    if (s.bad_expr >= 0)
      why = fmt::format("expression '{}' is {} at i={} t={:g}", s.exprs->texts()[static_cast<size_t>(s.bad_expr)],
                        s.values[static_cast<size_t>(s.bad_expr)], s.end_i, s.end_t);
    const Reply reply{
        s.bad_expr < 0,
        fmt::format("command source for '{}' ended ({}) after {} tick(s){}{}", s.controller, why, s.ticks,
                    s.started ? fmt::format(", last at {:.6f} s", s.last_us * 1e-6) : "",
                    s.ignored ? fmt::format("; {} message(s) from the bus on '{}' were ignored while it ran",
                                            s.ignored, s.channel)
                              : "")};
    give_back(s);
    if (reply.ok)
      log_.info(reply.message);
    else
      log_.warn(reply.message);
    answer(s.request_id, reply);
    sources_.erase(sources_.begin() + static_cast<std::ptrdiff_t>(k));
  }
}

void CommandSources::from_bus(Source& s, const lcm::ReceiveBuffer& rb) {
  if (s.echoes.received(message_digest(rb.data, rb.data_size))) return;
  if (s.ignored++ == 0)
    log_.warn(fmt::format("'{}': a message from the bus was ignored: the command source of '{}' ({}) owns this "
                          "channel until it ends; further ones are counted in its end (turret-cmd's Ctrl-C removes it)",
                          s.channel, s.controller, s.summary));
}

void CommandSources::give_back(Source& s) {
  if (s.endpoints) s.endpoints->divert(s.channel, {});
  s.endpoints = nullptr;
}

void CommandSources::end_for(const std::string& controller, const char* why) {
  for (auto& s : sources_)
    if (s->controller == controller && !s->end) {
      give_back(*s);
      s->end = why;
      s->slot = nullptr;
      s->fresh = false;
    }
}

void CommandSources::end_all(const char* why) {
  for (auto& s : sources_)
    if (!s->end) {
      give_back(*s);
      s->end = why;
      s->slot = nullptr;
      s->fresh = false;
    }
}

size_t CommandSources::active() const {
  size_t n = 0;
  for (const auto& s : sources_) n += s->end ? 0 : 1;
  return n;
}

int64_t CommandSources::ticks(const std::string& controller) const {
  int64_t n = -1;
  for (const auto& s : sources_)
    if (s->controller == controller) n = s->ticks;
  return n;
}

}  // namespace lcm_control::cm
