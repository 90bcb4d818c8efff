"""LCM over UDP multicast for Python where LCM's own module is not installed.

Debian packages LCM for C, C++, Java and Lua but not Python. With LCM's module
(`pip install lcm`) use `lcm.LCM(url)`; this class offers the part of its API
the examples use (publish, subscribe, unsubscribe, handle_timeout), speaking the same wire
format (LCM's "LC02" short messages, which hold any message up to 65,000
bytes; larger, fragmented ones are skipped) on the same `udpm://` URL.
"""
import os
import re
import select
import socket
import struct

_MAGIC_SHORT = 0x4C433032  # "LC02"


class LCM:
    def __init__(self, url=None):
        url = url or os.environ.get("LCM_DEFAULT_URL") or "udpm://239.255.76.67:7667?ttl=0"
        m = re.fullmatch(r"udpm://([\d.]+):(\d+)(?:\?(.*))?", url)
        if not m:
            raise ValueError(f"{url}: only udpm://GROUP:PORT?ttl=N URLs are supported")
        self.group, self.port = m.group(1), int(m.group(2))
        options = dict(kv.split("=", 1) for kv in (m.group(3) or "").split("&") if "=" in kv)
        ttl = int(options.get("ttl", "0"))
        self._recv = socket.socket(socket.AF_INET, socket.SOCK_DGRAM, socket.IPPROTO_UDP)
        self._recv.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        self._recv.bind(("", self.port))
        membership = struct.pack("4s4s", socket.inet_aton(self.group), socket.inet_aton("0.0.0.0"))
        self._recv.setsockopt(socket.IPPROTO_IP, socket.IP_ADD_MEMBERSHIP, membership)
        self._send = socket.socket(socket.AF_INET, socket.SOCK_DGRAM, socket.IPPROTO_UDP)
        self._send.setsockopt(socket.IPPROTO_IP, socket.IP_MULTICAST_TTL, ttl)
        self._send.setsockopt(socket.IPPROTO_IP, socket.IP_MULTICAST_LOOP, 1)
        self._seq = 0
        self._handlers = []

    def publish(self, channel, data):
        packet = struct.pack(">II", _MAGIC_SHORT, self._seq) + channel.encode() + b"\0" + data
        if len(packet) > 65507:
            raise ValueError(f"{channel}: {len(data)} bytes is more than one datagram; use LCM's own module")
        self._seq = (self._seq + 1) & 0xFFFFFFFF
        self._send.sendto(packet, (self.group, self.port))

    def subscribe(self, channel_regex, handler):
        """handler(channel, data) for every message whose channel matches the whole regex, as LCM does; returns
        the subscription, for unsubscribe()."""
        subscription = (re.compile(channel_regex), handler)
        self._handlers.append(subscription)
        return subscription

    def unsubscribe(self, subscription):
        self._handlers = [s for s in self._handlers if s is not subscription]

    def handle_timeout(self, timeout_ms):
        """Handles one message if one comes within timeout_ms; returns 1 if it did, 0 on timeout."""
        ready, _, _ = select.select([self._recv], [], [], timeout_ms / 1000.0)
        if not ready:
            return 0
        packet = self._recv.recv(65536)
        if len(packet) < 9 or struct.unpack(">I", packet[:4])[0] != _MAGIC_SHORT:
            return 1  # a fragment of a large message, or not LCM
        end = packet.find(b"\0", 8)
        if end < 0:
            return 1
        channel, data = packet[8:end].decode(errors="replace"), packet[end + 1:]
        for regex, handler in self._handlers:
            if regex.fullmatch(channel):
                handler(channel, data)
        return 1
