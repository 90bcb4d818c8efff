"""One bench/run: the robots, one controller_manager per robot for the loop benchmarks, the results as they come
(r), the load average sampled along, and the order the benchmarks run in."""
import os
import sys
import tempfile
import threading
import time

from . import async_update, goal_intake, lockstep, physics, realtime, round_trip, stiff
from .ports import lcm_url
from .processes import Proc, load_and_start
from .robots import MODELS, models


class Bench:
    def __init__(self, args):
        self.args = args
        self.smoke = args.smoke
        self.bin = os.path.join(os.path.abspath(args.build_dir), "bin")
        self.tmp = tempfile.mkdtemp(prefix="lcm_control_bench_")
        self.models = models(self.tmp)
        self.names = ["turret_bot", "chain7"] if self.smoke else MODELS
        self.cms = {}  # name -> (Proc, url)
        self.load = []
        self.r = {}

    def exe(self, name):
        return os.path.join(self.bin, name)

    def sample_load(self):
        with open("/proc/loadavg") as f:
            self.load.append(float(f.read().split()[0]))

    def say(self, text):
        if not hasattr(self, "t_say"):
            self.t_say = time.monotonic()
        print(f"bench: [{time.monotonic() - self.t_say:5.0f} s] {text}", file=sys.stderr, flush=True)

    SPIN_US = realtime.SPIN_US
    RT_PRIORITY = realtime.RT_PRIORITY

    # setup for 2, 3, 5: one controller_manager per model, controllers running
    def shm_url(self, name):
        return f"shm:bench-{os.getpid()}-{name}"

    def start_managers(self):
        # Each model's manager twice: as shipped (the hardware loop read on the loop thread), and with LCM's receive
        # thread in between (--hardware-reader lcm, as before), for the lockstep comparison in 3.
        # A third with the hardware loop over shared memory (--hardware-url shm:NAME, issue 34).
        for name in self.names:
            urdf, config, _ = self.models[name]
            for key, reader in ((name, "direct"), ((name, "lcm"), "lcm"), ((name, "shm"), "direct")):
                url = lcm_url()
                extra = ["--hardware-url", self.shm_url(name)] if key == (name, "shm") else []
                p = Proc([self.exe("controller_manager"), "--urdf", urdf, "--config", config, "--lcm-url", url,
                          "--hardware-reader", reader, "--log-level", "warn" if not self.smoke else "info"] + extra,
                         f"controller_manager[{name}, {reader}{', shm' if extra else ''}]")
                self.cms[key] = (p, url)
        for key in self.cms:
            name = key if isinstance(key, str) else key[0]
            p, url = self.cms[key]
            if self.smoke:
                p.wait_for("ready (", 20)
            load_and_start(self.exe("cmctl"), url, self.models[name][2])

    def run_all(self):
        t0 = time.monotonic()
        done = threading.Event()

        def sampler():  # the 1-minute load average every 5 s, next to the samples at each section
            while not done.wait(5):
                self.sample_load()
        threading.Thread(target=sampler, daemon=True).start()
        try:
            self._run_all()
        finally:
            done.set()
        self.run_s = time.monotonic() - t0

    def _run_all(self):
        self.say("1/4 physics overhead (in-process)")
        physics.run(self)
        stiff.run(self)
        async_update.run(self)
        goal_intake.run(self)
        self.say("starting one controller_manager per model")
        self.start_managers()
        self.say("2/4 loop round trip vs bare LCM and raw UDP")
        round_trip.run(self)
        self.say("3/4 lockstep throughput (+ peak RSS)")
        lockstep.run(self)
        self.say("4/4 real-time pacing" + ("" if self.smoke else " (60 s as shipped and 60 s at SCHED_FIFO, then up to 9 x 15 s with the hardware loop apart)"))
        fifo = realtime.fifo_permitted()
        realtime.run(self)
        if fifo:
            realtime.run(self, fifo=True)
        realtime.quiet(self, fifo)
        for name, (p, _) in self.cms.items():
            rc = p.stop(5)
            if rc != 0:
                raise RuntimeError(f"controller_manager[{name}] exited with {rc}:\n{p.output()[-3000:]}")
