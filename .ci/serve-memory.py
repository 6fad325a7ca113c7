#!/usr/bin/env python3
"""The memory of `vstf serve` under the requests a page on
any site could send them: 30 renders at distinct speeds, then 50 at once,
of a 259,588-prism scene (the repository's sphere-relativistic fixture with
its sphere tessellated at 511 segments). Prints the server's peak resident
memory (VmHWM) after each round; the default --cache-mb is 512.

    python3 .ci/serve-memory.py target/release/vstf [CACHE_MB]

Not run by .ci/run (it takes a minute of both cores); docs/security.md
quotes its figures.
"""
import json, os, re, socket, subprocess, sys, tempfile, threading

vstf = os.path.abspath(sys.argv[1])
cache_mb = sys.argv[2] if len(sys.argv) > 2 else "512"
repo = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
root = tempfile.mkdtemp(prefix="vstf-serve-memory-")
os.makedirs(os.path.join(root, "fixtures"))
f = json.load(open(os.path.join(repo, "fixtures", "sphere-relativistic.json")))
f["objects"][0]["mesh"] = {"sphere": {"radius": 1.0, "segments": 511}}
f["checks"] = []
json.dump(f, open(os.path.join(root, "fixtures", "big.json"), "w"))

server = subprocess.Popen([vstf, "--root", root, "serve", "--port", "0", "--cache-mb", cache_mb],
                          stdout=subprocess.PIPE, text=True)
addr = re.search(r"http://([^/ ]+)/", server.stdout.readline()).group(1)
host, port = addr.rsplit(":", 1)


def get(path):
    s = socket.create_connection((host, int(port)), timeout=600)
    s.sendall(f"GET {path} HTTP/1.1\r\nHost: {addr}\r\nConnection: close\r\n\r\n".encode())
    data = b""
    while chunk := s.recv(65536):
        data += chunk
    return int(data.split()[1]), data


def peak_mb():
    for line in open(f"/proc/{server.pid}/status"):
        if line.startswith("VmHWM"):
            return int(line.split()[1]) / 1024


try:
    token = re.search(rb"const TOKEN = '([0-9a-f]+)'", get("/")[1]).group(1).decode()
    render = f"/api/render?fixture=big&view=view&token={token}&speed="
    for k in range(30):
        assert get(render + str(0.5 + k / 100))[0] == 200
    print(f"30 distinct speeds: peak {peak_mb():.0f} MiB (cache budget {cache_mb} MiB)")
    answers = []
    threads = [threading.Thread(target=lambda k=k: answers.append(get(render + str(0.2 + k / 1000))[0]))
               for k in range(50)]
    [t.start() for t in threads]
    [t.join() for t in threads]
    counts = {c: answers.count(c) for c in sorted(set(answers))}
    print(f"50 renders at once: {counts}, peak {peak_mb():.0f} MiB")
finally:
    server.kill()
