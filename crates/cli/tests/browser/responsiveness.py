#!/usr/bin/env python3
"""How responsive `rtl lab` is: time from a change of settings to the first frame, frames per second,
and the latency of other requests while it renders.

usage: responsiveness.py URL [WIDTH] [STRATEGY]   (a running `rtl lab`; default 200, mis)
"""
import json, sys, time, urllib.request

url = sys.argv[1].rstrip("/")
width = sys.argv[2] if len(sys.argv) > 2 else "200"
strategy = sys.argv[3] if len(sys.argv) > 3 else "mis"

def call(path, method="GET"):
    t = time.perf_counter()
    with urllib.request.urlopen(urllib.request.Request(url + path, method=method), timeout=30) as r:
        body = r.read()
    return json.loads(body), time.perf_counter() - t

def first_frame(seed):
    t0 = time.perf_counter()
    gen = call(f"/api/render/settings?strategy={strategy}&width={width}&seed={seed}", "POST")[0]["generation"]
    while True:
        f = call("/api/render/state")[0]["frame"]
        if f["generation"] == gen and f["id"] > 0:
            return time.perf_counter() - t0, gen
        time.sleep(0.005)

firsts = []
for seed in range(1, 6):
    t, gen = first_frame(seed)
    firsts.append(t)
    time.sleep(0.3)
# frames over 5 s of one render, and the latency of other requests meanwhile
t, gen = first_frame(99)
ids, lat = set(), []
t0 = time.perf_counter()
while time.perf_counter() - t0 < 5.0:
    s, dt = call("/api/render/state")
    ids.add(s["frame"]["id"])
    lat.append(call("/api/mc/list")[1])
    time.sleep(0.05)
f = s["frame"]
print(f"{width}x{width} {strategy}: first frame after a change of settings "
      f"{min(firsts)*1e3:.0f}-{max(firsts)*1e3:.0f} ms over {len(firsts)} changes; "
      f"{len(ids)/5.0:.1f} frames/s over 5 s ({f['spp']} spp, {f['rays_per_second']/1e6:.2f} M rays/s); "
      f"other requests meanwhile: median {sorted(lat)[len(lat)//2]*1e3:.1f} ms, max {max(lat)*1e3:.1f} ms")
