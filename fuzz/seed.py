"""Assembles the seed corpora (called by seed.sh): seed.py SIM_DIR CORPUS_DIR.

Folder formats are one input whose files are separated by NUL bytes, in the order of the
target's list in fuzz/src/lib.rs (an empty piece: that file is absent). The live target's
events are encoded as fuzz/src/lib.rs `live` decodes them."""
import glob, json, math, os, struct, sys, hashlib

SIM, OUT = sys.argv[1], sys.argv[2]
FIX = "tests/fixtures/import"
MAX = 64 * 1024

def cut(data, limit):
    """At most `limit` bytes, ending at a line end."""
    if len(data) <= limit:
        return data
    data = data[:limit]
    return data[: data.rfind(b"\n") + 1]

def put(target, data):
    d = os.path.join(OUT, target)
    os.makedirs(d, exist_ok=True)
    name = "seed-" + hashlib.sha1(data).hexdigest()[:16]
    with open(os.path.join(d, name), "wb") as f:
        f.write(data)

def read(path):
    with open(path, "rb") as f:
        return f.read()

def one(target, path, prefix=b""):
    put(target, prefix + cut(read(path), MAX))

def cut_folder(names, dirs):
    """The files of a folder, each cut to its share of 60 KiB, joined by NUL."""
    per = (MAX - 4096) // len(names)
    pieces = []
    for n in names:
        p = next((os.path.join(d, n) for d in dirs if os.path.exists(os.path.join(d, n))), None)
        pieces.append(cut(read(p), per) if p else b"")
    return b"\0".join(pieces)

def folder(target, names, dirs):
    """One seed from the files of a folder, each cut to its share of 64 KiB."""
    per = MAX // len(names)
    pieces = []
    for n in names:
        p = next((os.path.join(d, n) for d in dirs if os.path.exists(os.path.join(d, n))), None)
        pieces.append(cut(read(p), per) if p else b"")
    put(target, b"\0".join(pieces))

SL = ["Accelerometer.csv", "Gyroscope.csv", "Magnetometer.csv", "Orientation.csv",
      "Gravity.csv", "Location.csv", "Metadata.csv", "TotalAcceleration.csv"]
PHY = ["Accelerometer.csv", "Gyroscope.csv", "Magnetometer.csv", "Location.csv",
       "meta/device.csv", "meta/time.csv", "Raw Data.csv"]
OX = ["accelerometer.csv", "stepcounter.csv", "stats.csv"]
TYREX = ["accelerometer.txt", "gyroscope-calibrated.txt", "gyroscope.txt",
         "magnetometer-calibrated.txt", "magnetometer.txt", "rotation-vector.txt",
         "attitude.txt", "record.properties", "description.txt", "truth.csv"]
UBI = ["acc.csv", "gyr.csv", "mag.csv", "truth.json"]
WAW = ["sensors.csv", "steps.csv", "segments.csv"]

for sc in ["straight", "gnss-city"]:
    s = os.path.join(SIM, sc)
    one("pdrlog", f"{s}/pdr-log")
    # A valid JSON array: its first records (one line each), closed.
    lines = read(f"{s}/sensor-logger-json").split(b"\n")
    kept, size = [], 2
    for l in lines:
        l = l.rstrip(b",]")
        if size + len(l) + 2 > MAX or not l.strip(b"[ "):
            break
        kept.append(l)
        size += len(l) + 2
    put("sensor_logger_json", b",\n".join(kept) + b"]\n")
    one("gnss_logger", f"{s}/gnss-logger")
    one("get_sensor_data", f"{s}/get-sensor-data")
    one("ms_indoor", f"{s}/ms-indoor")
    one("xio", f"{s}/xio")
    for f in ["sensor-logger", "sensor-logger-ios"]:
        folder("sensor_logger_csv", SL, glob.glob(f"{s}/{f}/*/"))
    folder("phyphox", PHY, glob.glob(f"{s}/phyphox/*/"))
    folder("oxford", OX, glob.glob(f"{s}/oxford/*/"))
    for f in ["tyrex", "tyrex-ios"]:
        folder("tyrex", TYREX, glob.glob(f"{s}/{f}/*/"))
    folder("ubicomp13", UBI, glob.glob(f"{s}/ubicomp13/*/"))
    folder("weallwalk", WAW, glob.glob(f"{s}/weallwalk/*/"))
    # recipe: the recipe's JSON, then the header-less files it reads.
    plain = glob.glob(f"{s}/plain-csv/*/")
    rec = read(f"{s}/plain-csv/recipe.json")
    put("recipe", rec + b"\0" + cut_folder(["acc.csv", "gyr.csv", "mag.csv", "bar.csv"], plain))
    put("recipe", b"\0" + cut_folder(["acc.csv", "gyr.csv", "mag.csv", "bar.csv"], plain))
    # sniff: one file, its name chosen by the first byte (SNIFF_NAMES in lib.rs).
    for k, f in [(1, "pdr-log"), (2, "sensor-logger-json"), (0, "gnss-logger"),
                 (0, "get-sensor-data"), (0, "ms-indoor"), (3, "xio")]:
        one("sniff", f"{s}/{f}", bytes([k]))

# The fixtures.
one("pdrlog", f"{FIX}/walk.pdrlog")
one("sensor_logger_json", f"{FIX}/sensor_logger.json")
one("gnss_logger", f"{FIX}/gnss_logger.txt")
one("get_sensor_data", f"{FIX}/get_sensor_data.txt")
one("ms_indoor", f"{FIX}/ms_indoor.txt")
one("xio", f"{FIX}/xio_foot.csv")
for k, f in [(1, "walk.pdrlog"), (2, "sensor_logger.json"), (0, "gnss_logger.txt"),
             (0, "get_sensor_data.txt"), (0, "ms_indoor.txt"), (3, "xio_foot.csv")]:
    one("sniff", f"{FIX}/{f}", bytes([k]))
for d in ["sensor_logger_android", "sensor_logger_ios"]:
    folder("sensor_logger_csv", SL, [f"{FIX}/{d}"])
folder("phyphox", PHY, [f"{FIX}/phyphox"])
put("phyphox", b"\0" * 6 + cut(read(f"{FIX}/phyphox_semicolon/Raw Data.csv"), MAX))
put("phyphox", cut(read(f"{FIX}/phyphox_linear/Linear Accelerometer.csv"), MAX))
folder("oxford", OX, glob.glob(f"{FIX}/oxford/*/"))

# The step-length profile: the built-in lines, and a fitted profile.
def profile(name, wa, wb, ra, rb, pts):
    return json.dumps({
        "version": 1, "name": name,
        "profile": {"walking": {"a": wa, "b": wb, "f_lo": 1.2, "f_hi": 2.2},
                    "running": {"a": ra, "b": rb, "f_lo": 2.7, "f_hi": 3.6},
                    "min_m": 0.2, "max_m": 2.5},
        "walking_points": pts, "running_points": []}, indent=2).encode()
put("profile_json", profile("Built-in", 0.25, 0.17, 0.9, -1.5, []))
put("profile_json", profile("Me", 0.298, 0.203, 0.9, -1.5, [[1.6, 0.6], [1.9, 0.68]]))

# The live session's events (see `live` in lib.rs).
def f(v):
    return b"\0" + struct.pack("<d", v)

def t(ms, prev):
    d = ms - prev
    if d == int(d) and 0 <= d <= 111:
        return bytes([16 + int(d)])
    return f(ms)

def quat(alpha, beta, gamma):
    """[x, y, z, w] of Rz(alpha)·Rx(beta)·Ry(gamma), degrees."""
    def q(axis, a):
        h = math.radians(a) / 2
        v = [0.0, 0.0, 0.0]
        v[axis] = math.sin(h)
        return (math.cos(h), *v)
    def mul(a, b):
        w1, x1, y1, z1 = a
        w2, x2, y2, z2 = b
        return (w1*w2 - x1*x2 - y1*y2 - z1*z2, w1*x2 + x1*w2 + y1*z2 - z1*y2,
                w1*y2 - x1*z2 + y1*w2 + z1*x2, w1*z2 + x1*y2 - y1*x2 + z1*w2)
    w, x, y, z = mul(mul(q(2, alpha), q(0, beta)), q(1, gamma))
    return [x, y, z, w]

def live(events_path, ios, generic, fixes):
    ev = json.load(open(events_path))["events"]
    out = bytearray([1 if ios else 0])
    prev, n = 0.0, 0
    for e in ev:
        if len(out) > MAX - 200:
            break
        if e["type"] == "orientation":
            n += 1
            if n % 10 != 1:
                continue
            if generic:
                out += bytes([3]) + t(e["t"], prev) + b"".join(f(v) for v in quat(e["alpha"], e["beta"], e["gamma"]))
            else:
                out += bytes([2]) + t(e["t"], prev) + bytes([1 | 2 | 4 | 8]) + f(e["alpha"]) + f(e["beta"]) + f(e["gamma"])
        else:
            a = [e["x"], e["y"], e["z"]]
            rot = [e["alpha"], e["beta"], e["gamma"]]
            if generic:
                sign = -1.0 if ios else 1.0
                out += bytes([1]) + t(e["t"], prev) + b"".join(f(sign * v) for v in a) + bytes([1]) + b"".join(f(math.radians(v)) for v in rot)
            else:
                out += bytes([0]) + t(e["t"], prev) + bytes([3]) + b"".join(f(v) for v in a + rot)
        prev = e["t"]
        if fixes and n % 100 == 1 and e["type"] == "orientation":
            # A fix a second: the simulated walk starts near Florence.
            k = n // 100
            out += bytes([4]) + f(e["t"]) + f(43.7697 + 1e-5 * k) + f(11.2563 + 1e-5 * k) + f(8.0) + bytes([1]) + f(50.0)
            prev = e["t"]
        if n % 300 == 299:
            out += bytes([6, 7, 8])
    # A gap, then the views.
    out += bytes([5]) + f(prev) + f(prev + 60000.0) + bytes([6, 7, 8])
    put("live", bytes(out))

for sc in ["straight", "gnss-city"]:
    s = os.path.join(SIM, sc)
    live(f"{s}/events.json", False, False, sc == "gnss-city")
    live(f"{s}/events-ios.json", True, False, sc == "gnss-city")
    live(f"{s}/events.json", False, True, sc == "gnss-city")

# zip: archives of the fixtures and of simulated folders, deflated and stored, with and without
# data descriptors (zipfile writes them when its output cannot seek), each at most 64 KiB.
import io, zipfile

class Unseekable(io.RawIOBase):
    def __init__(self):
        self.buf = bytearray()
    def writable(self):
        return True
    def write(self, b):
        self.buf += b
        return len(b)

def zipped(files, method, stream):
    out = Unseekable() if stream else io.BytesIO()
    with zipfile.ZipFile(out, "w", method) as z:
        for name, data in files:
            z.writestr(name, data)
    return bytes(out.buf) if stream else out.getvalue()

def tree(root, prefix):
    files = []
    for dirpath, _, names in os.walk(root):
        for n in sorted(names):
            p = os.path.join(dirpath, n)
            files.append((prefix + os.path.relpath(p, root), cut(read(p), 8 * 1024)))
    return files

sources = [tree(f"{FIX}/sensor_logger_android", "Recording/"), tree(f"{FIX}/phyphox", ""),
           [("walk.pdrlog", read(f"{FIX}/walk.pdrlog"))]]
for files in sources:
    for method in [zipfile.ZIP_DEFLATED, zipfile.ZIP_STORED]:
        for stream in [False, True]:
            z = zipped(files, method, stream)
            if len(z) <= MAX:
                put("zip", z)
