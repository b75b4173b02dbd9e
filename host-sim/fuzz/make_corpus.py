#!/usr/bin/env python3
"""Writes a small seed corpus for every fuzz target into host-sim/fuzz/corpus/<target>/
(generated, not stored in the repository): one or a few valid files of each format, so
that libFuzzer starts from inputs that reach deep into each parser."""
import json, math, os, struct, sys, zlib

root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "corpus")
x = [math.sin(0.3 * i) + 0.1 * math.cos(1.7 * i) for i in range(64)]


def put(target, name, data):
    d = os.path.join(root, target)
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, name), "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())


def sub(ty, b):
    out = struct.pack("<II", ty, len(b)) + b
    return out + b"\0" * ((8 - len(out) % 8) % 8)


def matrix(name, values, cls=6, ty=9, fmt="<d"):
    body = sub(6, struct.pack("<II", cls, 0))
    body += sub(5, struct.pack("<ii", len(values), 1))
    body += sub(1, name.encode())
    body += sub(ty, b"".join(struct.pack(fmt, v) for v in values))
    return struct.pack("<II", 14, len(body)) + body


hdr = b"MATLAB 5.0 MAT-file, Platform: corpus".ljust(116, b" ") + b"\0" * 8 + struct.pack("<H", 0x0100) + b"IM"
plain = hdr + matrix("X097_DE_time", x) + matrix("X097RPM", [1797.0])
put("mat", "plain.mat", plain)
el = matrix("X097_DE_time", x)
put("mat", "compressed.mat", hdr + struct.pack("<II", 15, len(zlib.compress(el))) + zlib.compress(el))
put("mat", "int16.mat", hdr + matrix("X097_DE_time", [int(1000 * v) for v in x], cls=10, ty=3, fmt="<h"))

def struct_matrix(name, fields):
    """A 1x1 struct `name` with fields [(field name, miMATRIX element with an empty name)]."""
    fl = 16
    body = sub(6, struct.pack("<II", 2, 0)) + sub(5, struct.pack("<ii", 1, 1)) + sub(1, name.encode())
    body += struct.pack("<HHi", 5, 4, fl)  # small element: field name length
    body += sub(1, b"".join(f.encode().ljust(fl, b"\0") for f, _ in fields))
    body += b"".join(m for _, m in fields)
    return struct.pack("<II", 14, len(body)) + body


def char_matrix(text):
    body = sub(6, struct.pack("<II", 4, 0)) + sub(5, struct.pack("<ii", 1, len(text))) + sub(1, b"")
    body += sub(4, text.encode("utf-16-le"))
    return struct.pack("<II", 14, len(body)) + body


mfpt = struct_matrix("bearing", [("sr", matrix("", [97656.0])), ("gs", matrix("", x)), ("load", matrix("", [270.0])), ("rate", matrix("", [25.0]))])
put("mat", "mfpt_struct.mat", hdr + mfpt)
z = zlib.compress(mfpt)
put("mat", "mfpt_struct_compressed.mat", hdr + struct.pack("<II", 15, len(z)) + z)
y = struct_matrix("Y", [("Name", char_matrix("vibration_1")), ("Data", matrix("", x, cls=7, ty=7, fmt="<f"))])
put("mat", "paderborn_nested.mat", hdr + struct_matrix("N15_M07_F10_K001_1", [("Y", y)]))

data = b"".join(struct.pack("<f", v) for v in x)
fmt = struct.pack("<HHIIHH", 3, 1, 1000, 4000, 4, 32)
wav = b"RIFF" + struct.pack("<I", 4 + 8 + len(fmt) + 8 + len(data)) + b"WAVE"
wav += b"fmt " + struct.pack("<I", len(fmt)) + fmt + b"data" + struct.pack("<I", len(data)) + data
put("wav", "float.wav", wav)
pcm = b"".join(struct.pack("<h", int(8000 * v)) for v in x)
fmt16 = struct.pack("<HHIIHH", 1, 1, 1000, 2000, 2, 16)
put("wav", "pcm16.wav", b"RIFF" + struct.pack("<I", 36 + len(pcm)) + b"WAVE" + b"fmt " + struct.pack("<I", 16) + fmt16 + b"data" + struct.pack("<I", len(pcm)) + pcm)

for descr, pack, shape in [("<f8", "<d", "(64,)"), ("<f4", "<f", "(32, 2)")]:
    h = "{'descr': '%s', 'fortran_order': False, 'shape': %s, }" % (descr, shape)
    h = h + " " * ((64 - (10 + len(h) + 1) % 64) % 64) + "\n"
    put("npy", descr[1:] + ".npy", b"\x93NUMPY\x01\x00" + struct.pack("<H", len(h)) + h.encode() + b"".join(struct.pack(pack, v) for v in x))

put("csv", "one.csv", "accel_m_s2\n" + "".join(f"{v!r}\n" for v in x))
put("csv", "time.csv", "time_s,accel_m_s2,accel_g\n" + "".join(f"{i/1000},{v!r},{v/9.80665!r}\n" for i, v in enumerate(x)))
put("ims_snapshot", "snapshot", "".join("\t".join(f"{v * (k + 1):.3f}" for k in range(4)) + "\n" for v in x))
put("ims_snapshot", "snapshot8", "".join("\t".join(f"{v * (k + 1):.3f}" for k in range(8)) + "\n" for v in x))
put("ims_features", "vaibhav.csv", "Timestamp,B1_rms,B2_rms,B3_rms,B4_rms\n" + "".join(f"2004-02-12 10:{i:02d}:39,{abs(v):.4f},{abs(v)*2:.4f},0.1,0.2\n" for i, v in enumerate(x[:20])))
put("ims_features", "chocho.csv", ",Bearing 1,Bearing 2,Bearing 3,Bearing 4\n" + "".join(f"2004-02-12 10:{i:02d}:39,{abs(v):.4f},0.1,0.2,0.3\n" for i, v in enumerate(x[:20])))
put("sidecar", "sidecar.json", json.dumps({"format": "wearsim-output", "format_version": 1, "fs": 20000.0, "n_samples": 64, "columns": ["accel_m_s2"], "units": {"accel_m_s2": "m/s^2"}, "rpm": 1500.0, "complete": True}))
put("sidecar", "minimal.json", json.dumps({"fs": 12000}))
# feature_table: the sidecar, a NUL byte, then the CSV (docs/feature-tables.md).
_side = {"format": "wearsim-feature-table", "format_version": 1, "source": "fuzz seed", "bearing": {"preset": "ims-za2115", "id": "b1"}, "channel": "ch1", "unit": "g", "rpm": 2000.0, "radial_load_n": 26689.0, "sample_rate_hz": 20000.0, "snapshot_samples": 20480, "snapshot_interval_s": 600.0, "failure_mode": "outer-race", "n_snapshots": 12}
_rows = "".join(f"{i},{600.0 * i},{0.07 + 0.001 * i},{3.1 + 0.01 * i},{(0.3 + 0.002 * i) / (0.07 + 0.001 * i)!r},{0.01 * i},{0.3 + 0.002 * i},{0.02 + 0.0005 * i}\n" for i in range(12))
put("feature_table", "table", json.dumps(_side) + "\0" + "snapshot,time_s,rms,kurtosis,crest_factor,skewness,peak,band_2000_8000_hz\n" + _rows)


def frame(kind, fmt, seq, first, scale, payload):
    h = struct.pack("<BBBBIIIfHH", 1, kind, fmt, 0, seq, first, 0, scale, len(payload), 0)
    body = h + payload
    return bytes([0xA5, 0x5A, 0x57, 0x53]) + body + struct.pack("<I", zlib.crc32(body) & 0xFFFFFFFF)


start = b"thesis-61810".ljust(24, b"\0") + struct.pack("<QfIII", 7, 20000.0, 2, 64, 1)
start = start.ljust(48, b"\0")
s = frame(1, 0, 0, 0, 0.0, start)
s += frame(2, 1, 1, 0, 1.0, b"".join(struct.pack("<f", v) for v in x[:32]))
s += frame(2, 1, 2, 32, 1.0, b"".join(struct.pack("<f", v) for v in x[32:]))
end = struct.pack("<IIIQIII", 64, 2, 0, 1000, 25000000, 10, 0)
s += frame(3, 0, 3, 0, 0.0, end.ljust(32, b"\0"))
put("frame", "stream.bin", s)
put("frame", "i16.bin", frame(1, 0, 0, 0, 0.0, start) + frame(2, 2, 1, 0, 0.001, b"".join(struct.pack("<h", int(1000 * v)) for v in x)))
print(f"corpus written to {root}", file=sys.stderr)
