#!/usr/bin/env python3
"""What the viewer tests read back, with the standard library alone:

  viewer_check.py wait LOG CONDITION [SECONDS]
      polls the viewer's --edit-log (viewer/event_log.h) until CONDITION, a
      Python expression, holds; exit 1 with the log's last lines on timeout
      or, with VIEWER_PID set, once that process is gone.
      Names in it: frames (dicts of the frame lines, numbers as numbers),
      f (the last frame, {} before the first; its area is the image's
      rectangle x,y,w,h in window units), edits (the edit lines), messages
      (the panel's message texts), asks (the loads the panel asked about),
      outside (why the eye is out of the room; "" back in), readouts (dicts
      with box [x, y, w, h] and lines).
  viewer_check.py sane SHOT.xwd X,Y,W,H
      exit 0 when the rectangle of an X screenshot (xwd) holds a plausible
      render: not black, many colours; prints its figures.
  viewer_check.py cameras FILE
      the eye of every camera the viewer printed (C) into FILE: "x y z" a line.

and, imported by the tests' own checks: read_log, read_png, read_xwd,
image_stats, crop.
"""
import json
import os
import struct
import sys
import time
import zlib


def _number(v):
    try:
        return int(v)
    except ValueError:
        try:
            return float(v)
        except ValueError:
            return v


def read_log(path):
    """The event log as a list of (word, fields); a text= field runs to the
    end of its line."""
    out = []
    try:
        text = open(path, encoding="utf-8", errors="replace").read()
    except FileNotFoundError:
        return out
    lines = text.split("\n")[:-1]  # a last line without its newline is still being written
    for line in lines:
        if not line.strip():
            continue
        head, sep, rest_text = line.partition(" text=")
        parts = head.split()
        fields = {}
        for p in parts[1:]:
            k, _, v = p.partition("=")
            fields[k] = _number(v)
        if sep:
            fields["text"] = rest_text
        out.append((parts[0], fields))
    return out


def log_names(entries):
    frames = [f for w, f in entries if w == "frame"]
    for f in frames:
        if "area" in f:
            f["area"] = [int(round(float(v))) for v in str(f["area"]).split(",")]
    readouts = []
    for w, f in entries:
        if w == "readout":
            r = dict(f)
            r["box"] = [float(v) for v in str(f["box"]).split(",")]
            r["lines"] = f.get("text", "").split("|")
            readouts.append(r)
    return {
        "frames": frames,
        "f": frames[-1] if frames else {},
        "edits": [f for w, f in entries if w == "edit"],
        "messages": [f.get("text", "") for w, f in entries if w == "message"],
        "asks": [f.get("load", "") for w, f in entries if w == "ask"],
        "outside": [f.get("text", "") for w, f in entries if w == "outside"],
        "readouts": readouts,
        "scenes": [f.get("text", "") for w, f in entries if w == "scene"],
        "panels": [f for w, f in entries if w == "panel"],
        "tips": [f.get("text", "") for w, f in entries if w == "tip"],
        "states": [f.get("text", "") for w, f in entries if w == "state"],
    }


def running(pid):
    """The process is there and not a zombie (exited, waiting to be reaped)."""
    try:
        stat = open(f"/proc/{pid}/stat").read()
    except OSError:
        return False
    return stat[stat.rindex(")") + 2:][:1] != "Z"


def wait(log, condition, seconds=60.0, pid=None):
    """True once the condition holds; False after `seconds`, or once the
    process `pid` (the viewer) is gone."""
    end = time.monotonic() + seconds
    while True:
        names = log_names(read_log(log))
        try:
            if eval(condition, {}, names):
                return True
        except (KeyError, IndexError, TypeError):
            pass  # the fields it reads are not there yet
        if time.monotonic() > end or (pid and not running(pid)):
            return False
        time.sleep(0.05)


def read_png(path):
    """(w, h, rgb bytes) of an 8-bit RGB PNG without interlace."""
    data = open(path, "rb").read()
    pos, idat, w, h = 8, b"", 0, 0
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            w, h, depth, colour = struct.unpack(">IIBB", body[:10])
            assert depth == 8 and colour == 2, "8-bit RGB expected"
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    raw, stride, rows, prev = zlib.decompress(idat), w * 3, [], bytearray(w * 3)
    for y in range(h):
        f = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        if f == 2:
            line = bytearray((a + b) & 255 for a, b in zip(line, prev))
        elif f != 0:
            for i in range(stride):
                a = line[i - 3] if i >= 3 else 0
                b, c = prev[i], (prev[i - 3] if i >= 3 else 0)
                if f == 1:
                    line[i] = (line[i] + a) & 255
                elif f == 3:
                    line[i] = (line[i] + (a + b) // 2) & 255
                elif f == 4:
                    p = a + b - c
                    pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                    line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line))
        prev = line
    return w, h, b"".join(rows)


def read_xwd(path):
    """(w, h, rgb bytes) of an xwd screenshot (TrueColor, 24 or 32 bits a
    pixel, least significant byte first: blue, green, red)."""
    data = open(path, "rb").read()
    h = struct.unpack(">25I", data[:100])
    size, w, ht, byte_order, bpp, bpl, ncolours = h[0], h[4], h[5], h[7], h[11], h[12], h[19]
    red, green, blue = h[14], h[15], h[16]
    assert byte_order == 0 and (red, green, blue) == (0xFF0000, 0xFF00, 0xFF), "BGR(X) expected"
    step = bpp // 8
    assert step in (3, 4) and bpl >= w * step, "24 or 32 bits a pixel expected"
    pixels = data[size + 12 * ncolours:]
    out = bytearray(w * ht * 3)
    for y in range(ht):
        row = pixels[y * bpl:y * bpl + w * step]
        o = y * w * 3
        out[o:o + w * 3:3] = row[2::step]
        out[o + 1:o + w * 3:3] = row[1::step]
        out[o + 2:o + w * 3:3] = row[0::step]
    return w, ht, bytes(out)


def crop(img, x, y, w, h):
    iw, ih, px = img
    x, y, w, h = int(x), int(y), int(w), int(h)
    assert 0 <= x and 0 <= y and x + w <= iw and y + h <= ih, "rectangle outside the image"
    return w, h, b"".join(px[(r * iw + x) * 3:(r * iw + x + w) * 3] for r in range(y, y + h))


def image_stats(img):
    """Mean level, the fraction of black pixels (every channel < 4) and the
    number of distinct colours (5 bits a channel)."""
    w, h, px = img
    n = w * h
    mean = sum(px) / (3.0 * n) if n else 0.0
    black = 0
    colours = set()
    for k in range(0, len(px), 3):
        r, g, b = px[k], px[k + 1], px[k + 2]
        black += r < 4 and g < 4 and b < 4
        colours.add((r >> 3, g >> 3, b >> 3))
    return {"mean": mean, "black": black / n if n else 1.0, "colours": len(colours)}


def sane(img):
    """A render, not a black or flat image: the camera is in the room."""
    s = image_stats(img)
    return s["mean"] > 12 and s["black"] < 0.6 and s["colours"] > 40, s


def cameras(path):
    text, pos, dec = open(path).read(), 0, json.JSONDecoder()
    out = []
    while True:
        start = text.find("{", pos)
        if start < 0:
            return out
        obj, pos = dec.raw_decode(text, start)
        if "camera" in obj:
            out.append(obj["camera"]["position"])


def main(argv):
    if argv[1] == "wait":
        seconds = float(argv[4]) if len(argv) > 4 else 60.0
        if wait(argv[2], argv[3], seconds, os.environ.get("VIEWER_PID")):
            return 0
        tail = open(argv[2]).read().splitlines()[-4:] if os.path.exists(argv[2]) else ["(no log)"]
        print(f"timed out after {seconds:.0f} s waiting for: {argv[3]}", file=sys.stderr)
        print("\n".join(tail), file=sys.stderr)
        return 1
    if argv[1] == "sane":
        rect = [int(v) for v in argv[3].split(",")]
        ok, s = sane(crop(read_xwd(argv[2]), *rect))
        print(f"{os.path.basename(argv[2])}: mean {s['mean']:.1f}, black {100 * s['black']:.1f} %, "
              f"{s['colours']} colours{'' if ok else ' -- NOT A SANE RENDER'}")
        return 0 if ok else 1
    if argv[1] == "cameras":
        for p in cameras(argv[2]):
            print(*p)
        return 0
    print(__doc__, file=sys.stderr)
    return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv))
