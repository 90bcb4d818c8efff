"""A free LCM URL for each benchmark's bus."""
import random
import socket


def free_udp_port():
    """A random UDP port below the kernel's ephemeral range, checked free with an exclusive bind. A port from that
    range can be taken, between the check and LCM's bind, by any socket a sendto binds on its own (every LCM
    publisher's), and LCM then fails with "Address already in use" (test/support/lcm_test.cpp does the same)."""
    try:
        with open("/proc/sys/net/ipv4/ip_local_port_range") as f:
            low = int(f.read().split()[0])
    except (OSError, ValueError, IndexError):
        low = 32768
    rng = random.SystemRandom()
    for _ in range(1000):
        port = rng.randrange(10000, low)
        with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:
            try:
                s.bind(("0.0.0.0", port))
                return port
            except OSError:
                continue
    raise RuntimeError("no free UDP port below the ephemeral range in 1000 tries")


def lcm_url():
    return f"udpm://239.255.76.67:{free_udp_port()}?ttl=0"
