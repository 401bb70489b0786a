#!/usr/bin/env python3
"""Memory of a live ringdyn-server under many readers and bursts (memory.sh).

  memprobe.py held PORT PID N REQUEST_FILE REF_SHA256
      N connections send the request in REQUEST_FILE (raw HTTP, one per
      connection) and do not read: the server holds every answer it could
      not send yet.  Once its RSS has settled, every answer is read whole;
      prints {"rss_before_mb", "peak_growth_mb", "bodies_ok", "statuses"}.
      peak_growth_mb: VmHWM over the wait (reset through /proc/PID/clear_refs
      when allowed, else the largest VmRSS sampled) minus VmRSS before.
      bodies_ok: every body (gunzipped when the answer says gzip) has the
      SHA-256 REF_SHA256.
  memprobe.py burst PORT PID K BYTES
      K clients POST a scene of about BYTES at once (a modal scene with a
      block modal does not read: parsed whole, then refused 422), then the
      server is left idle; prints {"rss_before_mb", "rss_peak_mb",
      "rss_after_mb", "seconds_to_settle", "statuses"}.
"""
import gzip
import hashlib
import json
import socket
import sys
import threading
import time


def status_kb(pid, key):
    with open(f"/proc/{pid}/status") as f:
        for line in f:
            if line.startswith(key + ":"):
                return int(line.split()[1])
    return 0


def rss_mb(pid):
    return status_kb(pid, "VmRSS") / 1024.0


def reset_hwm(pid):
    try:
        with open(f"/proc/{pid}/clear_refs", "w") as f:
            f.write("5")
        return True
    except OSError:
        return False


def read_answer(sock):
    """(status, body) of one HTTP/1.1 answer with Content-Length, read whole."""
    data = b""
    while b"\r\n\r\n" not in data:
        chunk = sock.recv(65536)
        if not chunk:
            return 0, b""
        data += chunk
    head, body = data.split(b"\r\n\r\n", 1)
    lines = head.decode("latin-1").split("\r\n")
    status = int(lines[0].split()[1])
    headers = {k.strip().lower(): v.strip() for k, v in (x.split(":", 1) for x in lines[1:])}
    length = int(headers.get("content-length", "0"))
    parts = [body]
    have = len(body)
    while have < length:
        chunk = sock.recv(1 << 20)
        if not chunk:
            break
        parts.append(chunk)
        have += len(chunk)
    body = b"".join(parts)
    if headers.get("content-encoding") == "gzip":
        body = gzip.decompress(body)
    return status, body


def settle(pid, samples, limit_s=30.0, quiet_s=1.0):
    """Waits until VmRSS has not changed by 1 MB for quiet_s; samples it."""
    t0 = last_change = time.monotonic()
    last = rss_mb(pid)
    while time.monotonic() - t0 < limit_s:
        time.sleep(0.1)
        now = rss_mb(pid)
        samples.append(now)
        if abs(now - last) > 1.0:
            last, last_change = now, time.monotonic()
        elif time.monotonic() - last_change >= quiet_s:
            break
    return time.monotonic() - t0


def held(port, pid, n, request_file, ref):
    request = open(request_file, "rb").read()
    before = rss_mb(pid)
    cleared = reset_hwm(pid)
    socks = []
    for _ in range(n):
        s = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
        s.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 8192)
        s.connect(("127.0.0.1", port))
        s.sendall(request)
        socks.append(s)
    samples = [before]
    settle(pid, samples, quiet_s=1.0)
    peak = status_kb(pid, "VmHWM") / 1024.0 if cleared else max(samples)
    answers = []

    def reader(s):
        s.settimeout(60)
        try:
            st, body = read_answer(s)
            answers.append((st, hashlib.sha256(body).hexdigest() == ref))
        except OSError:
            answers.append((0, False))
        s.close()

    threads = [threading.Thread(target=reader, args=(s,)) for s in socks]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    statuses = [a[0] for a in answers]
    ok = len(answers) == n and all(a[1] for a in answers)
    return {"rss_before_mb": round(before, 1), "peak_growth_mb": round(peak - before, 1),
            "hwm_reset": cleared, "bodies_ok": ok, "statuses": sorted(set(statuses))}


def burst(port, pid, k, size):
    head, tail = '{"analysis":"modal","physics":{"gas":{"crank_deg":[', "]}}}"
    values, n = [], len(head) + len(tail)
    while n + 14 <= size:
        values.append("%.9f" % (len(values) * 1e-3))
        n += len(values[-1]) + 1
    body = (head + ",".join(values) + tail).encode()
    request = (b"POST /api/v1/jobs HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: application/json\r\n"
               b"Connection: close\r\nContent-Length: %d\r\n\r\n" % len(body)) + body
    before = rss_mb(pid)
    cleared = reset_hwm(pid)
    statuses, samples = [], [before]
    go = threading.Barrier(k)

    def client():
        try:
            s = socket.create_connection(("127.0.0.1", port))
            go.wait()
            s.sendall(request)
            s.settimeout(60)
            statuses.append(read_answer(s)[0])
            s.close()
        except OSError:
            statuses.append(0)

    threads = [threading.Thread(target=client) for _ in range(k)]
    for t in threads:
        t.start()
    while any(t.is_alive() for t in threads):
        samples.append(rss_mb(pid))
        time.sleep(0.02)
    for t in threads:
        t.join()
    peak = status_kb(pid, "VmHWM") / 1024.0 if cleared else max(samples)
    t_settle = settle(pid, samples, limit_s=10.0, quiet_s=2.0)
    return {"body_bytes": len(body), "rss_before_mb": round(before, 1),
            "rss_peak_mb": round(peak, 1), "rss_after_mb": round(rss_mb(pid), 1),
            "seconds_to_settle": round(t_settle, 1), "statuses": sorted(set(statuses))}


def main():
    mode, port, pid = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
    if mode == "held":
        out = held(port, pid, int(sys.argv[4]), sys.argv[5], sys.argv[6])
    else:
        out = burst(port, pid, int(sys.argv[4]), int(sys.argv[5]))
    print(json.dumps(out))


if __name__ == "__main__":
    main()
