// bus/shm_link: the hardware loop's shared memory. Bytes arrive whole and newest-first across threads and processes,
// a wait ends on a message or a watched descriptor and never outlives its timeout, the file goes with the last user
// (a killed one too), a writer killed mid-write is taken over, hostile slot contents are skipped, and the Bus and
// Endpoints carry hardware messages there and mirror them to LCM when asked.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <pwd.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "bus/bus.hpp"
#include "bus/endpoints.hpp"
#include "bus/shm_link.hpp"
#include "lcm_control/hardware_state_t.hpp"
#include "rt/clock.hpp"
#include "test/support/lcm_test.hpp"
#include "test/support/shm_segment.hpp"

namespace lcm_control {
namespace {

std::string unique_name() {
  static int n = 0;
  return "test-" + std::to_string(getpid()) + "-" + std::to_string(n++);
}

std::vector<uint8_t> bytes(const std::string& s) { return std::vector<uint8_t>(s.begin(), s.end()); }

struct Inbox {
  std::vector<std::string> got;
  ShmLink::Handler handler() {
    return [this](const lcm::ReceiveBuffer& rb) {
      got.emplace_back(static_cast<const char*>(rb.data), rb.data_size);
    };
  }
};

TEST(ShmLink, BytesGoToTheOtherEndNotBackAndTheNewestWins) {
  const std::string name = unique_name();
  ShmLink a(name), b(name);
  EXPECT_TRUE(std::filesystem::exists(a.path()));
  Inbox at_a, at_b;
  a.subscribe("r/hardware/command", at_a.handler());
  b.subscribe("r/hardware/state", at_b.handler());
  a.subscribe("r/hardware/state", at_a.handler());  // a's own messages are not handed back to it
  const auto one = bytes("state one"), two = bytes("state two, longer");
  ASSERT_EQ(a.publish("r/hardware/state", one.data(), one.size()), 0);
  EXPECT_TRUE(b.has_new());
  EXPECT_FALSE(a.has_new());
  ASSERT_EQ(a.publish("r/hardware/state", two.data(), two.size()), 0);
  EXPECT_EQ(b.handle_queued(), 1);
  EXPECT_EQ(at_b.got, std::vector<std::string>{"state two, longer"});
  EXPECT_EQ(b.handle_queued(), 0) << "taken once";
  EXPECT_TRUE(at_a.got.empty());
  const auto cmd = bytes("command");
  ASSERT_EQ(b.publish("r/hardware/command", cmd.data(), cmd.size()), 0);
  EXPECT_EQ(a.handle_queued(), 1);
  EXPECT_EQ(at_a.got, std::vector<std::string>{"command"});
  // A message larger than a slot is refused and counted; the slot keeps the last one.
  std::vector<uint8_t> huge(ShmLink::kSlotBytes + 1);
  EXPECT_EQ(a.publish("r/hardware/state", huge.data(), huge.size()), -1);
  EXPECT_EQ(a.too_large(), 1);
}

TEST(ShmLink, APatternBindsTheSlotsNamedLaterAndUnsubscribeStopsDelivery) {
  const std::string name = unique_name();
  ShmLink a(name), b(name);
  std::vector<std::string> channels;
  const int id = b.subscribe_pattern("r/hardware/.*", [&](const lcm::ReceiveBuffer&, const std::string& ch) {
    channels.push_back(ch);
  });
  const auto m = bytes("x");
  a.publish("r/hardware/state", m.data(), m.size());
  a.publish("other/thing", m.data(), m.size());
  EXPECT_EQ(b.handle_queued(), 1);
  EXPECT_EQ(channels, std::vector<std::string>{"r/hardware/state"});
  b.unsubscribe(id);
  a.publish("r/hardware/state", m.data(), m.size());
  EXPECT_EQ(b.handle_queued(), 0);
  EXPECT_THROW(b.subscribe_pattern("(", [](const lcm::ReceiveBuffer&, const std::string&) {}), BusError);
}

TEST(ShmLink, AWaitEndsAtAMessageFromAnotherThreadAndOtherwiseAtItsTimeout) {
  const std::string name = unique_name();
  ShmLink a(name), b(name);
  Inbox at_b;
  b.subscribe("s", at_b.handler());
  int64_t t0 = monotonic_us();
  EXPECT_FALSE(b.wait_us(30000));
  const int64_t waited = monotonic_us() - t0;
  EXPECT_GE(waited, 29000);
  EXPECT_LT(waited, 500000);
  std::thread writer([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    const auto m = bytes("hello");
    a.publish("s", m.data(), m.size());
  });
  t0 = monotonic_us();
  EXPECT_TRUE(b.wait_us(5000000));
  EXPECT_LT(monotonic_us() - t0, 2000000);
  writer.join();
  EXPECT_EQ(b.handle_queued(), 1);
}

TEST(ShmLink, AWatchedDescriptorEndsTheWaitUntilDrained) {
  const std::string name = unique_name();
  ShmLink a(name);
  int p[2];
  ASSERT_EQ(pipe(p), 0);
  a.watch_fd(p[0]);
  EXPECT_FALSE(a.wait_us(20000));
  EXPECT_FALSE(a.fd_ready());
  ASSERT_EQ(write(p[1], "x", 1), 1);
  EXPECT_TRUE(a.wait_us(5000000));
  EXPECT_TRUE(a.fd_ready());
  char c;
  ASSERT_EQ(read(p[0], &c, 1), 1);
  a.fd_drained();
  EXPECT_FALSE(a.wait_us(20000)) << "nothing left to read";
  close(p[0]);
  close(p[1]);
}

double thread_cpu_ms() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return t.tv_sec * 1e3 + t.tv_nsec / 1e6;
}

// Lockstep's waits yield the CPU first; with no answer for ShmLink::kYieldUs they sleep at once from then on, so a
// paused peer costs no CPU, until a wait ends within kYieldUs again.
TEST(ShmLink, AYieldingWaitKeepsItsTimeoutSleepsWhileThePeerIsSilentAndYieldsAgainWhenItAnswers) {
  const std::string name = unique_name();
  ShmLink a(name), b(name);
  Inbox at_b;
  b.subscribe("s", at_b.handler());
  b.yield_first(true);
  EXPECT_TRUE(b.yields_next());
  int64_t t0 = monotonic_us();
  EXPECT_FALSE(b.wait_us(30000));
  const int64_t waited = monotonic_us() - t0;
  EXPECT_GE(waited, 29000);
  EXPECT_LT(waited, 500000);
  EXPECT_FALSE(b.yields_next()) << "silent for longer than kYieldUs";
  const double cpu0 = thread_cpu_ms();
  for (int k = 0; k < 50; ++k) EXPECT_FALSE(b.wait_us(2000));
  EXPECT_LT(thread_cpu_ms() - cpu0, 20.0) << "50 waits of 2 ms on a silent peer should sleep, not yield 1 ms each";

  std::thread writer([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    const auto m = bytes("late");
    a.publish("s", m.data(), m.size());
  });
  t0 = monotonic_us();
  EXPECT_TRUE(b.wait_us(5000000)) << "a sleeping wait still ends at the message";
  EXPECT_LT(monotonic_us() - t0, 2000000);
  writer.join();
  EXPECT_EQ(b.handle_queued(), 1);
  EXPECT_FALSE(b.yields_next()) << "that answer took 20 ms";

  // A prompt peer: a thread answering each ping. Some wait ends within kYieldUs even on a loaded machine.
  std::atomic<bool> stop{false};
  Inbox at_a;  // outlives the thread: a's subscription keeps its handler
  a.subscribe("ping", at_a.handler());
  std::thread echo([&] {
    while (!stop)
      if (a.wait_us(1000) && a.handle_queued() > 0) a.publish("s", "pong", 4);
  });
  for (int k = 0; k < 1000 && !b.yields_next(); ++k) {
    b.publish("ping", "ping", 4);
    if (b.wait_us(100000)) b.handle_queued();
  }
  EXPECT_TRUE(b.yields_next()) << "no wait ended within kYieldUs in 1,000 round trips";
  stop = true;
  echo.join();

  b.yield_first(false);
  EXPECT_FALSE(b.yields_next());
}

// A lockstep exchange between two processes: every state answered once, in order, with the step it answers.
void ping_pong_in_order(bool yield_first) {
  const std::string name = unique_name();
  constexpr int kRounds = 2000;
  const pid_t child = fork();
  if (child == 0) {
    ShmLink cm(name);
    cm.yield_first(yield_first);
    int64_t last = -1;
    bool ok = true;
    cm.subscribe("state", [&](const lcm::ReceiveBuffer& rb) {
      int64_t step;
      std::memcpy(&step, rb.data, sizeof(step));
      ok = ok && step == last + 1;
      last = step;
      cm.publish("command", &step, sizeof(step));
    });
    const int64_t deadline = monotonic_us() + 20000000;
    while (last < kRounds - 1 && monotonic_us() < deadline)
      if (cm.wait_us(100000)) cm.handle_queued();
    _exit(ok && last == kRounds - 1 ? 0 : 1);
  }
  ShmLink sim(name);
  sim.yield_first(yield_first);
  int64_t answered = -1;
  sim.subscribe("command", [&](const lcm::ReceiveBuffer& rb) { std::memcpy(&answered, rb.data, sizeof(answered)); });
  int64_t step = 0;
  int64_t t0 = monotonic_us(), t1 = 0;
  int64_t republished = 0;
  while (step < kRounds && monotonic_us() - t0 < 20000000) {
    if (step == 1) t1 = monotonic_us();  // timed from the first answer: the child is up
    sim.publish("state", &step, sizeof(step));
    const int64_t sent = monotonic_us();
    while (answered != step && monotonic_us() - sent < 100000)
      if (sim.wait_us(100000)) sim.handle_queued();
    if (answered == step)
      ++step;
    else
      ++republished;  // the child had not subscribed yet: send it again, as sim_server's lockstep does
  }
  const double us = double(monotonic_us() - t1) / (kRounds - 1);
  int status = 0;
  waitpid(child, &status, 0);
  EXPECT_EQ(step, kRounds);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  std::printf("shm ping-pong between two processes%s: %.2f us a round trip (%lld republished while the peer came up)\n",
              yield_first ? ", waits yielding first" : "", us, static_cast<long long>(republished));
}

TEST(ShmLink, TwoProcessesPingPongInOrder) { ping_pong_in_order(false); }
TEST(ShmLink, TwoProcessesPingPongInOrderWhenTheirWaitsYieldFirst) { ping_pong_in_order(true); }

TEST(ShmLink, TheFileGoesWithTheLastUserEvenAfterAKill) {
  const std::string name = unique_name();
  std::string path;
  {
    ShmLink a(name);
    path = a.path();
    int ready[2];
    ASSERT_EQ(pipe(ready), 0);
    const pid_t child = fork();
    if (child == 0) {
      ShmLink b(name);
      const char c = 'r';
      if (write(ready[1], &c, 1) != 1) _exit(1);
      pause();
      _exit(0);
    }
    char c;
    ASSERT_EQ(read(ready[0], &c, 1), 1);
    kill(child, SIGKILL);
    waitpid(child, nullptr, 0);
    close(ready[0]);
    close(ready[1]);
    // Its reader place is taken by the next one that comes: kReaders more links open without running out.
    std::vector<std::unique_ptr<ShmLink>> more;
    for (int k = 0; k + 1 < ShmLink::kReaders; ++k) more.push_back(std::make_unique<ShmLink>(name));
    try {
      ShmLink too_many(name);
      ADD_FAILURE() << "a link past the reader places";
    } catch (const BusError& e) {
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("its own --namespace or shm:NAME"), std::string::npos) << e.what();
    }
    EXPECT_TRUE(std::filesystem::exists(path));
  }
  EXPECT_FALSE(std::filesystem::exists(path)) << "the last one to close it removes it";
  ShmLink again(name);  // and the next one makes it again
  EXPECT_TRUE(std::filesystem::exists(path));
}

// Another local user who makes the segment's file first (mode 0666, the right size) would read the robot's state and
// command its joints: the file is refused naming its owner, as is one of ours that others may write, or a link.
// Needs root, to be that other user (a process with uid 4242) and to give files away; skipped otherwise.
// A user of the machine made for the test (useradd), removed after it.
class TestUser {
 public:
  TestUser() : name_("lcmsq" + std::to_string(getpid() % 1000000)) {
    const std::string add = "useradd -M -N -s /usr/sbin/nologin " + name_ + " 2>/dev/null";
    if (std::system(add.c_str()) != 0) return;
    if (const passwd* pw = getpwnam(name_.c_str())) {
      uid_ = pw->pw_uid;
      gid_ = pw->pw_gid;
    }
  }
  ~TestUser() {
    if (uid_ >= 0) std::system(("userdel " + name_ + " 2>/dev/null").c_str());
  }
  TestUser(const TestUser&) = delete;
  TestUser& operator=(const TestUser&) = delete;
  const std::string& name() const { return name_; }
  int uid() const { return uid_; }
  int gid() const { return gid_; }

 private:
  std::string name_;
  int uid_ = -1, gid_ = -1;
};

TEST(ShmLink, ASegmentAnotherUserMadeOrLeftOpenToOthersIsRefusedByName) {
  if (geteuid() != 0) GTEST_SKIP() << "needs root";
  const TestUser squatter_user;
  ASSERT_GE(squatter_user.uid(), 0) << "useradd " << squatter_user.name() << " failed";
  const std::string name = unique_name();
  const std::string path = "/dev/shm/lcm_control." + name;
  const pid_t squatter = fork();
  if (squatter == 0) {
    if (setgid(gid_t(squatter_user.gid())) != 0 || setuid(uid_t(squatter_user.uid())) != 0) _exit(2);
    umask(0);
    const int fd = open(path.c_str(), O_RDWR | O_CREAT | O_EXCL, 0666);
    _exit(fd >= 0 && ftruncate(fd, off_t(64) << 20) == 0 ? 0 : 3);
  }
  int status = 0;
  ASSERT_EQ(waitpid(squatter, &status, 0), squatter);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "the squatter could not make " << path;
  auto refusal = [&] {
    try {
      ShmLink link(name);
    } catch (const BusError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  std::string why = refusal();
  EXPECT_NE(why.find(path), std::string::npos) << why;
  EXPECT_NE(why.find(fmt::format("it belongs to '{}', uid {}, not to this user", squatter_user.name(),
                                 squatter_user.uid())),
            std::string::npos)
      << why;
  EXPECT_NE(why.find("shm:ANOTHER_NAME"), std::string::npos) << why;
  // Ours, but open to others.
  ASSERT_EQ(chown(path.c_str(), 0, 0), 0);
  why = refusal();
  EXPECT_NE(why.find("its mode is 0666"), std::string::npos) << why;
  std::filesystem::remove(path);
  // A link to a file elsewhere.
  const std::string target = testing::temp_dir("shm_link") + "/target";
  { std::ofstream(target) << "x"; }
  std::filesystem::create_symlink(target, path);
  why = refusal();
  EXPECT_NE(why.find("is a link?"), std::string::npos) << why;
  std::filesystem::remove(path);
  // The file it makes itself is 0600 and its own.
  ShmLink ok(name);
  struct stat st {};
  ASSERT_EQ(stat(path.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 07777, 0600u);
}

TEST(ShmLink, AWriterKilledWhileWritingIsTakenOver) {
  const std::string name = unique_name();
  ShmLink a(name), b(name);
  Inbox at_b;
  b.subscribe("s", at_b.handler());
  const auto m = bytes("first");
  a.publish("s", m.data(), m.size());
  EXPECT_EQ(b.handle_queued(), 1);
  // What a writer killed between its two sequence stores leaves: an odd sequence, for good.
  testing::MappedSegment seg(a.path());
  ASSERT_TRUE(seg.ok());
  const int sequence_word = seg.sequence_word("s");
  ASSERT_GE(sequence_word, 0);
  auto* seq = reinterpret_cast<std::atomic<uint32_t>*>(&seg.words()[sequence_word]);
  seq->fetch_add(1);  // odd: a write begun and never finished
  EXPECT_FALSE(b.has_new()) << "a slot being written is not read";
  const auto m2 = bytes("after the dead writer");
  const int64_t t0 = monotonic_us();
  ASSERT_EQ(a.publish("s", m2.data(), m2.size()), 0);
  EXPECT_LT(monotonic_us() - t0, 2000000);
  EXPECT_EQ(a.stolen(), 1);
  EXPECT_EQ(b.handle_queued(), 1);
  EXPECT_EQ(at_b.got.back(), "after the dead writer");
}

TEST(ShmLink, AHostileSizeIsSkippedAndCountedAndAForeignFileIsNamed) {
  const std::string name = unique_name();
  ShmLink a(name), b(name);
  Inbox at_b;
  b.subscribe("s", at_b.handler());
  const auto m = bytes("0123456789abcdef");
  a.publish("s", m.data(), m.size());
  EXPECT_EQ(b.handle_queued(), 1);
  // Find the size word (16) beside the sequence and overwrite it with sizes past the slot, publishing in between.
  testing::MappedSegment seg(a.path());
  ASSERT_TRUE(seg.ok());
  const int size_word = seg.size_word("s");
  ASSERT_GE(size_word, 0);
  std::mt19937 rng(7);
  for (int round = 0; round < 100; ++round) {
    a.publish("s", m.data(), m.size());
    seg.words()[size_word] = ShmLink::kSlotBytes + 1 + rng() % 1000000;
    EXPECT_EQ(b.handle_queued(), 0);
  }
  EXPECT_EQ(b.malformed(), 100);
  EXPECT_EQ(at_b.got.size(), 1u);

  const std::string foreign = "/dev/shm/lcm_control." + unique_name();
  { std::FILE* f = std::fopen(foreign.c_str(), "w"); std::fputs("not ours", f); std::fclose(f); }
  chmod(foreign.c_str(), 0600);  // ours, as the program would make it: refused for what is in it
  try {
    ShmLink c(foreign.substr(std::string("/dev/shm/lcm_control.").size()));
    ADD_FAILURE() << "a foreign file was taken";
  } catch (const BusError& e) {
    EXPECT_NE(std::string(e.what()).find(foreign), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("remove the file"), std::string::npos) << e.what();
  }
  std::filesystem::remove(foreign);
}

TEST(ShmLink, UrlsNameASegmentPerNamespaceOrByName) {
  EXPECT_TRUE(is_shm_url("shm"));
  EXPECT_TRUE(is_shm_url("shm:robot-1"));
  EXPECT_FALSE(is_shm_url("udpm://239.255.76.67:7667"));
  EXPECT_EQ(shm_name_of("shm", "r0"), std::to_string(getuid()) + ".r0");
  EXPECT_EQ(shm_name_of("shm", ""), std::to_string(getuid()) + ".default");
  EXPECT_EQ(shm_name_of("shm:my_robot.1", "r0"), "my_robot.1");
  EXPECT_THROW(shm_name_of("shm:../etc", ""), BusError);
  EXPECT_THROW(shm_name_of("shm:", ""), BusError);
  EXPECT_EQ(hardware_url_for("shm", "udpm://239.255.76.67:7667", "/r1/"), "shm:" + std::to_string(getuid()) + ".r1");
}

TEST(ShmLink, TheBusCarriesTheHardwareLoopThereWakesForTheSharedBusAndMirrors) {
  const std::string url = testing::unique_lcm_url(), hw = "shm:" + unique_name();
  Bus sim(url, "r", hw, HardwareReader::Direct), cm(url, "r", hw, HardwareReader::Direct);
  ASSERT_NE(sim.hardware_shm(), nullptr);
  EXPECT_TRUE(sim.hardware_apart());
  EXPECT_EQ(sim.hardware_socket(), nullptr);
  Endpoints sim_hw(sim, Endpoints::On::Hardware), cm_hw(cm, Endpoints::On::Hardware);
  std::vector<int64_t> steps;
  cm_hw.subscribe<hardware_state_t>("r/hardware/state", [&](const hardware_state_t& s) { steps.push_back(s.step); });
  auto pub = sim_hw.publisher<hardware_state_t>("r/hardware/state");
  hardware_state_t st{};
  st.step = 7;
  ASSERT_EQ(pub.publish(st), 0);
  EXPECT_EQ(cm.wait_us(1000000), Bus::kHardwareReady);
  EXPECT_TRUE(cm.handle_us(0, 10));
  EXPECT_EQ(steps, std::vector<int64_t>{7});

  // The shared bus wakes the same wait.
  int heard = 0;
  cm.subscribe("r/e_stop", [&](const lcm::ReceiveBuffer&, const std::string&) { ++heard; });
  const uint8_t payload[4] = {1, 2, 3, 4};
  sim.lcm().publish("r/e_stop", payload, 4);
  const int64_t t0 = monotonic_us();
  int ready = 0;
  while (!(ready & Bus::kSharedReady) && monotonic_us() - t0 < 2000000) ready = cm.wait_us(100000);
  EXPECT_TRUE(ready & Bus::kSharedReady);
  EXPECT_TRUE(cm.handle_us(0, 10));
  EXPECT_EQ(heard, 1);

  // Mirrored at most 20 times a second: a burst of 50 gives one copy on LCM.
  lcm::LCM tap(url);
  int mirrored = 0;
  tap.subscribeFunction("r/hardware/state", +[](const lcm::ReceiveBuffer*, const std::string&, int* n) { ++*n; },
                        &mirrored);
  sim.mirror_hardware(20);
  for (int k = 0; k < 50; ++k) pub.publish(st);
  while (tap.handleTimeout(200) > 0) {
  }
  EXPECT_EQ(mirrored, 1);
  // Not on shared memory: the mirror is refused, naming the flag.
  Bus plain(url, "r", "", HardwareReader::Direct);
  try {
    plain.mirror_hardware(10);
    ADD_FAILURE() << "a mirror on LCM";
  } catch (const BusError& e) {
    EXPECT_NE(std::string(e.what()).find("--hardware-url shm"), std::string::npos) << e.what();
  }
}

// A state too large for the 1 MiB slot is not sent; the bus counts it and says once what to do, naming the file.
TEST(ShmLink, AMessageTooLargeForTheSlotIsCountedAndNamedOnce) {
  const std::string url = testing::unique_lcm_url(), hw = "shm:" + unique_name();
  Bus sim(url, "r", hw, HardwareReader::Direct);
  Endpoints sim_hw(sim, Endpoints::On::Hardware);
  auto pub = sim_hw.publisher<hardware_state_t>("r/hardware/state");
  hardware_state_t st{};
  st.num_actuators = 50000;  // 50,000 names of 16 characters and their values: about 1.9 MB
  st.name.assign(50000, "actuator_0000000");
  st.mode.assign(50000, 0);
  st.position.assign(50000, 0.0);
  st.velocity.assign(50000, 0.0);
  st.effort.assign(50000, 0.0);
  EXPECT_EQ(pub.publish(st), -1);
  EXPECT_EQ(pub.publish(st), -1);
  EXPECT_EQ(sim.hardware_refused(), 2);
  const std::string note = sim.hardware_loss_note();
  EXPECT_NE(note.find("could not send 2 message(s) through " + sim.hardware_shm()->path()), std::string::npos)
      << note;
  EXPECT_NE(note.find("give it an LCM --hardware-url"), std::string::npos) << note;
  EXPECT_EQ(sim.hardware_loss_note(), "") << "said once";
  // On LCM nothing is refused for its size here.
  Bus plain(url, "r", "", HardwareReader::Direct);
  EXPECT_EQ(plain.hardware_refused(), 0);
}

// Issue 51: what another process of the user can do to the segment, each detected and said once, the link going on
// (or, truncated, going silent as a lost peer would) and no process killed by SIGBUS.
TEST(ShmLink, EachAttackOnTheSegmentIsSaidOnceAndNoneKills) {
  const std::string name = unique_name();
  ShmLink a(name), b(name);  // a writes "s", b reads it; places 0 and 1
  Inbox at_b;
  b.subscribe("s", at_b.handler());
  auto send = [&](ShmLink& from, const std::string& text) {
    const auto m = bytes(text);
    return from.publish("s", m.data(), m.size());
  };
  ASSERT_EQ(send(a, "one"), 0);
  ASSERT_EQ(b.handle_queued(), 1);
  EXPECT_EQ(b.take_tampering_note(), "");
  testing::MappedSegment seg(a.path());
  ASSERT_TRUE(seg.ok());

  // b's reader place rewritten: its mask cleared (a would stop ringing it) and its pid changed.
  seg.words()[testing::MappedSegment::reader_mask_word(1)] = 0;
  seg.words()[testing::MappedSegment::reader_pid_word(1)] = 1;
  EXPECT_FALSE(b.has_new());
  ASSERT_EQ(send(a, "two"), 0);
  EXPECT_EQ(b.handle_queued(), 1) << "restored: still delivered";
  std::string note = b.take_tampering_note();
  EXPECT_NE(note.find("reader place 1 in " + a.path() + " was rewritten by another process (restored)"),
            std::string::npos)
      << note;
  EXPECT_EQ(b.take_tampering_note(), "") << "said once";

  // The slot held mid-write past 100 ms.
  auto* seq = reinterpret_cast<std::atomic<uint32_t>*>(&seg.words()[seg.sequence_word("s")]);
  seq->fetch_add(1);
  EXPECT_FALSE(b.has_new());
  std::this_thread::sleep_for(std::chrono::milliseconds(150));
  EXPECT_FALSE(b.has_new());
  note = b.take_tampering_note();
  EXPECT_NE(note.find("channel 's' in " + a.path() + " was held mid-write for over 100 ms"), std::string::npos)
      << note;
  seq->fetch_add(1);  // released
  ASSERT_EQ(send(a, "three"), 0);
  EXPECT_EQ(b.handle_queued(), 1);
  EXPECT_EQ(b.take_tampering_note(), "");

  // A second live writer on the channel (another process).
  int ready[2], done[2];
  ASSERT_EQ(pipe(ready), 0);
  ASSERT_EQ(pipe(done), 0);
  const pid_t other = fork();
  if (other == 0) {
    ShmLink c(name);
    const auto m = bytes("from the other writer");
    c.publish("s", m.data(), m.size());
    char x = 1;
    if (write(ready[1], &x, 1) != 1) _exit(2);
    if (read(done[0], &x, 1) != 1) _exit(3);  // alive until the parent has looked
    _exit(0);
  }
  char x = 0;
  ASSERT_EQ(read(ready[0], &x, 1), 1);
  EXPECT_EQ(b.handle_queued(), 1);
  ASSERT_EQ(send(a, "four"), 0);
  EXPECT_EQ(b.handle_queued(), 1);
  note = b.take_tampering_note();
  EXPECT_NE(note.find("channel 's' in " + a.path() + " is written by two live processes"), std::string::npos) << note;
  EXPECT_NE(note.find("pid " + std::to_string(other)), std::string::npos) << note;
  ASSERT_EQ(write(done[1], &x, 1), 1);
  int status = 0;
  ASSERT_EQ(waitpid(other, &status, 0), other);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  EXPECT_EQ(b.take_tampering_note(), "");

  // The file truncated under both: the accesses past its end read zeros instead of raising SIGBUS, the link goes
  // silent, each says so once.
  ASSERT_TRUE(seg.truncate(0));
  EXPECT_EQ(send(a, "five"), 0);  // faults inside, survives
  EXPECT_EQ(send(a, "six"), -1) << "silent from then on";
  EXPECT_FALSE(b.has_new());
  EXPECT_EQ(b.handle_queued(), 0);
  EXPECT_FALSE(b.wait_us(20000));
  for (ShmLink* link : {&a, &b}) {
    note = link->take_tampering_note();
    EXPECT_NE(note.find(a.path() + " was truncated under this process"), std::string::npos) << note;
    EXPECT_NE(note.find("held as on a lost peer"), std::string::npos) << note;
    EXPECT_EQ(link->take_tampering_note(), "");
  }
  EXPECT_EQ(at_b.got.back(), "four");
}

}  // namespace
}  // namespace lcm_control
