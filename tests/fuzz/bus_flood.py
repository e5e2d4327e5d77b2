#!/usr/bin/env python3
"""A junk flood on the H4 channels (tests/fuzz/README.md#the-campaign-under-a-flood):
LCM UDP small messages (magic LC02) at RATE messages/s for SECONDS, on the LCM group of
LCM_DEFAULT_URL's default (239.255.76.67:7667) with multicast ttl 0, so nothing leaves the
host; run it inside scripts/in-private-netns. Each message picks an H4 channel and one of:
random bytes (undecodable); a message recorded in LOG (lcm-logger's file, fingerprint and
fields intact) made foreign: a board pose or its corners for a pose id no campaign asks
for, a robot target of an unknown type, a capture request for a negative pose id, a joint
state or camera status an hour old.

    tests/fuzz/bus_flood.py LOG [--rate 2000] [--seconds 30] [--seed 1]

Prints what it sent by kind. Needs python3.
"""
import argparse
import collections
import random
import socket
import struct
import sys
import time

CHANNELS = ["H4_BOARD_POSE", "H4_BOARD_CORNERS", "H4_JOINT_STATE", "H4_CAPTURE_REQUEST",
            "H4_CAMERA_STATUS", "H4_ROBOT_TARGET"]


def read_log(path):
    """Recorded message bodies per channel (LCM log: sync 0xEDA1DA01, event number, time,
    channel length, data length, channel, data; big-endian)."""
    out = collections.defaultdict(list)
    with open(path, "rb") as f:
        data = f.read()
    i = 0
    while i + 28 <= len(data):
        sync, _, _, clen, dlen = struct.unpack_from(">IqqII", data, i)
        if sync != 0xEDA1DA01:
            break
        channel = data[i + 28:i + 28 + clen].decode(errors="replace")
        body = data[i + 28 + clen:i + 28 + clen + dlen]
        if channel in CHANNELS and len(out[channel]) < 200 and len(body) < 60000:
            out[channel].append(bytes(body))
        i += 28 + clen + dlen
    return out


def foreign(channel, body, rng, now_us):
    """A recorded message changed so that no campaign may take it (offsets after the
    8-byte fingerprint: utime at 8, pose_id at 16 where the type has one)."""
    b = bytearray(body)
    if channel in ("H4_BOARD_POSE", "H4_BOARD_CORNERS"):
        struct.pack_into(">q", b, 8, now_us)
        struct.pack_into(">q", b, 16, 100000 + rng.randrange(100000))
        return b, "foreign pose id"
    if channel == "H4_ROBOT_TARGET":
        struct.pack_into(">q", b, 8, now_us)
        struct.pack_into(">q", b, 16, rng.randrange(1000))
        b[24] = 5
        return b, "unknown target type"
    if channel == "H4_CAPTURE_REQUEST":
        struct.pack_into(">q", b, 8, now_us)
        struct.pack_into(">q", b, 16, -5)
        return b, "negative pose id"
    struct.pack_into(">q", b, 8, now_us - 3600 * 1000000)
    return b, "an hour old"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("log")
    ap.add_argument("--rate", type=float, default=2000)
    ap.add_argument("--seconds", type=float, default=30)
    ap.add_argument("--seed", type=int, default=1)
    a = ap.parse_args()
    recorded = read_log(a.log)
    rng = random.Random(a.seed)
    sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    sock.setsockopt(socket.IPPROTO_IP, socket.IP_MULTICAST_TTL, 0)
    sent = collections.Counter()
    start = time.monotonic()
    n = 0
    while True:
        elapsed = time.monotonic() - start
        if elapsed >= a.seconds:
            break
        due = int(elapsed * a.rate)
        while n < due:
            channel = rng.choice(CHANNELS)
            if recorded[channel] and rng.random() < 0.6:
                body, kind = foreign(channel, rng.choice(recorded[channel]), rng,
                                     int(time.time() * 1e6))
            else:
                body, kind = bytes(rng.randrange(256) for _ in range(rng.randrange(1, 200))), \
                    "random bytes"
            packet = struct.pack(">II", 0x4C433032, n & 0xFFFFFFFF) + channel.encode() + b"\0" + body
            try:
                sock.sendto(packet, ("239.255.76.67", 7667))
            except OSError as e:
                sent["send failed: " + e.strerror] += 1
            sent[f"{channel} {kind}"] += 1
            n += 1
        time.sleep(0.002)
    print(f"bus_flood: {n} messages in {time.monotonic() - start:.1f} s "
          f"({n / (time.monotonic() - start):.0f}/s)")
    for k, v in sorted(sent.items()):
        print(f"  {v:6d}  {k}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
