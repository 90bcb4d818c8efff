#!/usr/bin/env python3
"""Unicast injection into LCM, and the firewall that stops it (docs/security.md).

Two network namespaces joined by a veth pair: "robot" runs lcm-logger on a
ttl=0 udpm:// URL, "peer" is another machine on the robot's network. A plain
UDP datagram from the peer to the robot's address on the LCM port is logged as
a message (LCM binds its socket to 0.0.0.0:PORT). With scripts/lcm-firewall
installed in the robot's namespace it is not, while a local publisher still
is; allowing the veth interface lets the peer in again. Then with the multicast
route on the veth, as "Several computers" in the user guide sets it on eth0:
the firewall must still let the robot's own looped-back traffic through (it
dropped it once: iifname is then the veth, not lo), and --allow-from the peer
lets that peer in.

Needs root, ip (iproute2), nft (nftables) and lcm-logger; exits 77 (skipped)
without them. Prints a RELIABILITY line for test/reliability/run.
"""
import argparse
import os
import shutil
import signal
import socket
import struct
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "support"))
from netns import run, skip  # noqa: E402

GROUP = "239.255.76.67"



def lcm_packet(seq, channel, payload):
    return struct.pack(">II", 0x4C433032, seq) + channel.encode() + b"\0" + payload


def log_channels(path):
    """Channels of every event in an LCM log file."""
    out = []
    with open(path, "rb") as f:
        data = f.read()
    i = 0
    while i + 28 <= len(data):
        sync, _, _, clen, dlen = struct.unpack(">IqqII", data[i:i + 28])
        if sync != 0xEDA1DA01:
            break
        out.append(data[i + 28:i + 28 + clen].decode(errors="replace"))
        i += 28 + clen + dlen
    return out


class Net:
    """robot <-> peer over a veth pair, 10.218.X.1 and .2; everything removed by close()."""

    def __init__(self):
        tag = str(os.getpid() % 100000)
        self.robot, self.peer = f"lcmfw_r{tag}", f"lcmfw_p{tag}"
        self.robot_if, self.peer_if = f"lfr{tag}", f"lfp{tag}"
        octet = os.getpid() % 250 + 1
        self.robot_ip, self.peer_ip = f"10.218.{octet}.1", f"10.218.{octet}.2"
        self.made = []

    def open(self):
        for ns in (self.robot, self.peer):
            r = run("ip", "netns", "add", ns, check=False)
            if r.returncode != 0:
                skip(f"cannot create a network namespace: {r.stderr.strip()}")
            self.made.append(ns)
        run("ip", "link", "add", self.robot_if, "netns", self.robot, "type", "veth", "peer", "name", self.peer_if,
            "netns", self.peer)
        for ns, ifc, ip in ((self.robot, self.robot_if, self.robot_ip), (self.peer, self.peer_if, self.peer_ip)):
            self.ns(ns, "ip", "link", "set", "lo", "up")
            self.ns(ns, "ip", "addr", "add", ip + "/24", "dev", ifc)
            self.ns(ns, "ip", "link", "set", ifc, "up")
        self.ns(self.robot, "ip", "link", "set", "lo", "multicast", "on")
        self.ns(self.robot, "ip", "route", "add", "224.0.0.0/4", "dev", "lo")

    def ns(self, ns, *argv, check=True):
        return run("ip", "netns", "exec", ns, *argv, check=check)

    def close(self):
        for ns in self.made:
            run("ip", "netns", "del", ns, check=False)


def send_from(net, ns, code):
    net.ns(ns, sys.executable, "-c", code)


def trial(net, port, logdir, name):
    """lcm-logger in the robot's namespace; one datagram from the peer, one local multicast. Returns the channels logged."""
    path = os.path.join(logdir, name + ".lcm")
    url = f"udpm://{GROUP}:{port}?ttl=0"
    logger = subprocess.Popen(["ip", "netns", "exec", net.robot, "lcm-logger", f"--lcm-url={url}", "-f", path],
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    try:
        deadline = time.monotonic() + 15
        while not os.path.exists(path) and time.monotonic() < deadline:
            time.sleep(0.05)
        time.sleep(0.3)
        peer = (f"import socket; s=socket.socket(socket.AF_INET, socket.SOCK_DGRAM); "
                f"s.sendto({lcm_packet(1, 'INJECTED', struct.pack('>q', 7))!r}, ('{net.robot_ip}', {port}))")
        local = (f"import socket; s=socket.socket(socket.AF_INET, socket.SOCK_DGRAM); "
                 f"s.setsockopt(socket.IPPROTO_IP, socket.IP_MULTICAST_TTL, 0); "
                 f"s.sendto({lcm_packet(2, 'LOCAL', struct.pack('>q', 8))!r}, ('{GROUP}', {port}))")
        for _ in range(3):
            send_from(net, net.peer, peer)
            send_from(net, net.robot, local)
            time.sleep(0.1)
        time.sleep(0.5)
    finally:
        logger.send_signal(signal.SIGINT)
        try:
            logger.wait(10)
        except subprocess.TimeoutExpired:
            logger.kill()
            logger.wait()
    return log_channels(path) if os.path.exists(path) else []


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--source-dir", required=True)
    args = ap.parse_args()
    if os.geteuid() != 0:
        skip("needs root (network namespaces and nftables)")
    for tool in ("ip", "nft", "lcm-logger"):
        if not shutil.which(tool):
            skip(f"{tool} not found (scripts/setup installs it)")
    firewall = os.path.join(args.source_dir, "scripts", "lcm-firewall")
    port = 20000 + os.getpid() % 20000
    net = Net()
    failures = []
    with tempfile.TemporaryDirectory() as logdir:
        try:
            net.open()
            open_bus = trial(net, port, logdir, "open")
            net.ns(net.robot, firewall, "install", "--port", str(port))
            guarded = trial(net, port, logdir, "guarded")
            net.ns(net.robot, firewall, "install", "--port", str(port), "--allow-interface", net.robot_if)
            allowed = trial(net, port, logdir, "allowed")
            net.ns(net.robot, "ip", "route", "replace", "224.0.0.0/4", "dev", net.robot_if)
            net.ns(net.robot, firewall, "install", "--port", str(port))
            routed = trial(net, port, logdir, "routed")
            net.ns(net.robot, firewall, "install", "--port", str(port), "--allow-from", net.peer_ip)
            routed_peer = trial(net, port, logdir, "routed_peer")
            net.ns(net.robot, firewall, "remove")
        finally:
            net.close()

    def count(chs, name):
        return sum(1 for c in chs if c == name)

    print(f"no firewall:      injected {count(open_bus, 'INJECTED')}/3 logged, local {count(open_bus, 'LOCAL')}/3")
    print(f"lcm-firewall:     injected {count(guarded, 'INJECTED')}/3 logged, local {count(guarded, 'LOCAL')}/3")
    print(f"allow {net.robot_if}: injected {count(allowed, 'INJECTED')}/3 logged, local {count(allowed, 'LOCAL')}/3")
    if count(open_bus, "INJECTED") == 0:
        failures.append("without the firewall the peer's datagram was not logged: the test no longer shows the hole")
    if count(guarded, "INJECTED") != 0:
        failures.append("with lcm-firewall installed the peer's datagram still reached lcm-logger")
    if count(guarded, "LOCAL") == 0:
        failures.append("with lcm-firewall installed the local publisher was not heard: the rule breaks the bus")
    if count(allowed, "INJECTED") == 0:
        failures.append("--allow-interface did not let the allowed interface's datagram in")
    print(f"route on {net.robot_if}:  injected {count(routed, 'INJECTED')}/3 logged, local {count(routed, 'LOCAL')}/3")
    print(f"--allow-from peer: injected {count(routed_peer, 'INJECTED')}/3 logged, "
          f"local {count(routed_peer, 'LOCAL')}/3")
    if count(routed, "LOCAL") == 0:
        failures.append("with the multicast route on the veth, lcm-firewall dropped the host's own traffic")
    if count(routed, "INJECTED") != 0:
        failures.append("with the multicast route on the veth, the peer's datagram still reached lcm-logger")
    if count(routed_peer, "INJECTED") == 0 or count(routed_peer, "LOCAL") == 0:
        failures.append("--allow-from did not let the allowed peer in (or lost the local traffic)")
    blocked = 6 - count(guarded, "INJECTED") - count(routed, "INJECTED")
    print(f"RELIABILITY|security|unicast injection from another host, multicast route on lo and on a veth|tried=6|"
          f"ok={blocked}|crashes=0|hangs=0|accepted without a firewall {count(open_bus, 'INJECTED')}/3, with "
          f"scripts/lcm-firewall {count(guarded, 'INJECTED')}/3 (route on lo) and {count(routed, 'INJECTED')}/3 "
          f"(route on the veth); the host's own bus still heard {count(guarded, 'LOCAL')}/3 and "
          f"{count(routed, 'LOCAL')}/3; --allow-from the peer {count(routed_peer, 'INJECTED')}/3 in")
    for f in failures:
        print("FAILED: " + f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
