#!/usr/bin/env python3
"""Minimal reader of swell cache files (.swell, format version 1), written from
docs/cache-format.md alone. Needs python3-zstandard; checks checksums when
python3-xxhash is installed.

    python3 tools/swell_cache.py CACHE               # summary
    python3 tools/swell_cache.py CACHE --frame 7     # that frame as CSV
"""
import json
import os
import re
import struct
import sys

import zstandard

try:
    import xxhash
except ImportError:  # checksums are optional for this example
    xxhash = None

MAGIC = b"\x89SWL\r\n\x1a\n"
FLAG_SHUFFLE, FLAG_DELTA = 1, 2


class CacheError(Exception):
    pass


def _sections(encoding, ns, nsp):
    """(bytes, element size, components per particle) of each record section."""
    if encoding == 0:  # float32: surface x,y; splash x,y,vx,vy
        return [(ns * 8, 4, 2), (nsp * 16, 4, 4)]
    # quantized16: surface x,y u16; splash x,y u16; splash vx,vy f32
    return [(ns * 4, 2, 2), (nsp * 4, 2, 2), (nsp * 8, 4, 2)]


def _unfilter(raw, encoding, ns, nsp, flags):
    out = bytearray(len(raw))
    base = 0
    for size, elem, stride in _sections(encoding, ns, nsp):
        n = size // elem
        sec = raw[base:base + size]
        if flags & FLAG_SHUFFLE:  # byte planes -> interleaved elements
            for b in range(elem):
                out[base + b:base + size:elem] = sec[b * n:(b + 1) * n]
        else:
            out[base:base + size] = sec
        if flags & FLAG_DELTA:  # running sum per component, wrapping
            fmt = "<%d%s" % (n, "H" if elem == 2 else "I")
            vals = list(struct.unpack_from(fmt, out, base))
            mask = (1 << (8 * elem)) - 1
            for i in range(stride, n):
                vals[i] = (vals[i] + vals[i - stride]) & mask
            struct.pack_into(fmt, out, base, *vals)
        base += size
    return bytes(out)


def temporary_file_writer(path):
    """The PID in the name of a writer's temporary file `<name>.tmp-<pid>`, else 0."""
    m = re.search(r"\.tmp-([0-9]{1,9})$", os.path.basename(str(path)))
    return int(m.group(1)) if m and int(m.group(1)) > 0 else 0


class Cache:
    def __init__(self, path):
        self.path = path
        pid = temporary_file_writer(path)
        if pid:
            # As the C++ reader: a writer's temporary is never a cache, complete or not.
            try:
                os.kill(pid, 0)
                state = "still running"
            except ProcessLookupError:
                state = "no longer running: the next bake to that output removes it"
            except PermissionError:
                state = "still running"
            raise CacheError("%s: a temporary file of an unfinished write by process %d (%s), "
                             "not a cache; a cache appears under its own name only when complete"
                             % (path, pid, state))
        with open(path, "rb") as f:
            self.data = f.read()
        d = self.data
        if len(d) < 96 or d[:8] != MAGIC:
            raise CacheError("%s: not a swell cache" % path)
        (self.version, header_size, self.encoding, self.flags, x0, y0, x1, y1, self.dt,
         self.frame_interval, self.level, self.seed, self.max_position_error, meta_len,
         count, index_offset, header_sum) = struct.unpack_from("<IIII4fdIIQfIQQQ", d, 8)
        if self.version != 1:
            raise CacheError("%s: unsupported version %d" % (path, self.version))
        self.domain = (x0, y0, x1, y1)
        self.metadata = json.loads(d[96:96 + meta_len].decode("utf-8"))
        if xxhash and xxhash.xxh3_64_intdigest(d[:88] + d[96:96 + meta_len]) != header_sum:
            raise CacheError("%s: header checksum mismatch" % path)
        if index_offset + 40 * count + 8 != len(d):
            raise CacheError("%s: truncated or trailing data" % path)
        self.index = [struct.unpack_from("<QQQIIQ", d, index_offset + 40 * i) for i in range(count)]

    def __len__(self):
        return len(self.index)

    def frame(self, i):
        """Returns (surface [(x, y)], splash [(x, y, vx, vy)]) of frame i."""
        offset, csize, rsize, ns, nsp, checksum = self.index[i]
        raw = zstandard.ZstdDecompressor().decompress(self.data[offset:offset + csize],
                                                      max_output_size=rsize)
        rec = _unfilter(raw, self.encoding, ns, nsp, self.flags)
        if xxhash and xxhash.xxh3_64_intdigest(rec) != checksum:
            raise CacheError("%s: frame %d: checksum mismatch" % (self.path, i))
        if self.encoding == 0:
            s = struct.unpack_from("<%df" % (2 * ns), rec, 0)
            p = struct.unpack_from("<%df" % (4 * nsp), rec, 8 * ns)
            return list(zip(s[0::2], s[1::2])), list(zip(p[0::4], p[1::4], p[2::4], p[3::4]))
        x0, y0, x1, y1 = self.domain
        # Same arithmetic as the C++ reader: double, then rounded to float32.
        f32 = lambda v: struct.unpack("<f", struct.pack("<f", v))[0]
        qx = lambda q: f32(x0 + (x1 - x0) * (q / 65535.0))
        qy = lambda q: f32(y0 + (y1 - y0) * (q / 65535.0))
        s = struct.unpack_from("<%dH" % (2 * ns), rec, 0)
        pp = struct.unpack_from("<%dH" % (2 * nsp), rec, 4 * ns)
        pv = struct.unpack_from("<%df" % (2 * nsp), rec, 4 * ns + 4 * nsp)
        surface = [(qx(a), qy(b)) for a, b in zip(s[0::2], s[1::2])]
        splash = [(qx(a), qy(b), u, v) for a, b, u, v in zip(pp[0::2], pp[1::2], pv[0::2], pv[1::2])]
        return surface, splash


def main(argv):
    if len(argv) not in (2, 4) or (len(argv) == 4 and argv[2] != "--frame"):
        print(__doc__, file=sys.stderr)
        return 2
    try:
        c = Cache(argv[1])
        if len(argv) == 2:
            counts = [c.index[i][3] for i in range(len(c))]
            print(json.dumps({"version": c.version, "frames": len(c), "dt": c.dt,
                              "frame_interval": c.frame_interval, "seed": c.seed,
                              "surface_max": max(counts, default=0),
                              "checksums": "checked" if xxhash else "not checked"}))
            for i in range(len(c)):
                c.frame(i)
            return 0
        surface, splash = c.frame(int(argv[3]))
        print("kind,x,y,vx,vy")
        for x, y in surface:
            print("surface,%.9g,%.9g,," % (x, y))
        for x, y, vx, vy in splash:
            print("splash,%.9g,%.9g,%.9g,%.9g" % (x, y, vx, vy))
        return 0
    except (CacheError, OSError, zstandard.ZstdError, IndexError) as e:
        print("swell_cache.py: %s" % e, file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
