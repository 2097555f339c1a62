#!/usr/bin/env python3
"""Reader of swell cache files (.swell, format version 1), written from docs/cache-format.md.
It refuses what the C++ reader (cache/src/reader.cpp) refuses, in the same words. Needs
python3-zstandard and python3-xxhash (tools/setup installs both).

    python3 tools/swell_cache.py CACHE               # check every frame, as swell-cache verify
    python3 tools/swell_cache.py CACHE --frame 7     # that frame as CSV

A defect is one line on stderr, "swell_cache.py: CACHE: what is wrong", and exit status 1.
"""
import json
import math
import os
import re
import stat
import struct
import sys

try:
    import xxhash
    import zstandard
except ImportError as e:  # both required: every checksum is always checked
    why = "the Python module {0} is missing: install python3-{0} (tools/setup does)".format(e.name)
    if __name__ == "__main__":
        sys.exit("swell_cache.py: " + why)
    raise ImportError("tools/swell_cache.py: " + why) from e

MAGIC = b"\x89SWL\r\n\x1a\n"
FLAG_SHUFFLE, FLAG_DELTA = 1, 2
MAX_METADATA, MAX_RAW_FRAME, MAX_JSON_DEPTH = 16 << 20, 256 << 20, 64
HEADER = struct.Struct("<IIII4fdIIQfIQQQ")  # the fixed header from offset 8
ENTRY = struct.Struct("<QQQIIQ")  # offset, compressed size, raw size, ns, nsp, checksum
xxh3 = xxhash.xxh3_64_intdigest


class CacheError(ValueError):
    """A file that is not a readable cache; the message names the file and the defect."""


_STRING = re.compile(rb'"[^"\\]*(?:\\.[^"\\]*)*(?:"|\\?\Z)', re.DOTALL)  # closed or not
_NOT_BRACKET = bytes(c for c in range(256) if c not in b"[]{}")


def json_depth(text):
    """Most arrays and objects open at once in `text`, brackets in strings not counted, for any
    text, JSON or not (cache/include/swell/cache/json_depth.h); no recursion."""
    depth = deepest = 0
    for c in _STRING.sub(b"", text).translate(None, _NOT_BRACKET):
        if c in b"[{":
            depth += 1
            deepest = max(deepest, depth)
        elif depth:
            depth -= 1
    return deepest


def _json_number(parse):
    """As the C++ reader's JSON parser: refuses NaN and Infinity (Python's json takes them) and
    any number beyond the f64 range."""
    def checked(text):
        if not math.isfinite(float(text)):
            raise ValueError("not a JSON number: " + text)
        return parse(text)
    return checked


def _f32(v):
    return struct.unpack("<f", struct.pack("<f", v))[0]


def _f32_text(v):  # as C++ prints a float: the shortest digits that read back as the same value
    s = next(s for s in (repr(float("%.*g" % (p, v))) for p in range(1, 10)) if _f32(float(s)) == v)
    return s[:-2] if s.endswith(".0") else s


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
    """Opening checks the header, its checksum, the file size, the index and its checksum, as
    swell::cache::Reader does; frame(i) checks that frame's zstd sizes and checksum."""

    def __init__(self, path):
        self.path = path
        need = self._need
        pid = temporary_file_writer(path)
        if pid:  # as the C++ reader: a writer's temporary is never a cache, complete or not
            try:
                os.kill(pid, 0)
                state = "still running"
            except ProcessLookupError:
                state = "no longer running: the next bake to that output removes it"
            except PermissionError:
                state = "still running"
            need(False, "a temporary file of an unfinished write by process %d (%s), not a cache; "
                 "a cache appears under its own name only when complete" % (pid, state))
        try:
            fd = os.open(path, os.O_RDONLY | os.O_CLOEXEC)
        except OSError as e:
            raise self._fail("cannot open: %s" % (e.strerror or e)) from None
        try:
            need(stat.S_ISREG(os.fstat(fd).st_mode), "not a regular file")
            with open(fd, "rb", closefd=False) as f:
                d = self.data = f.read()
        finally:
            os.close(fd)
        size = len(d)
        # The header and its checksum, then its fields (readHeaderBytes, decodeHeader).
        need(size >= 96, "truncated: %d bytes, shorter than the 96-byte header" % size)
        need(d[:8] == MAGIC, "not a swell cache (bad magic)")
        (self.version, header_size, self.encoding, self.flags, x0, y0, x1, y1, self.dt,
         self.frame_interval, self.level, self.seed, self.max_position_error, meta_len,
         count, index_offset, header_sum) = HEADER.unpack_from(d, 8)
        need(self.version == 1, "format version %d is not readable by this program (reads up to 1)"
             % self.version)
        need(meta_len <= MAX_METADATA and header_size == 96 + meta_len, "header damaged: metadata "
             "length %d disagrees with header size %d" % (meta_len, header_size))
        need(header_size <= size, "truncated inside the header metadata")
        meta = d[96:header_size]
        need(xxh3(d[:88] + meta) == header_sum,
             "header checksum mismatch (header damaged, or the file was never finished)")
        need(self.encoding <= 1, "unknown encoding %d" % self.encoding)
        need(not self.flags & ~(FLAG_SHUFFLE | FLAG_DELTA), "unknown flags %d" % self.flags)
        self.domain = (x0, y0, x1, y1)
        need(all(map(math.isfinite, self.domain)) and x1 > x0 and y1 > y0,
             "header damaged: invalid domain bounds")
        need(self.dt > 0 and math.isfinite(self.dt) and self.frame_interval > 0,
             "header damaged: invalid dt or frame interval")
        depth = json_depth(meta)  # before parsing: json.loads recurses once per level
        need(depth <= MAX_JSON_DEPTH, "header metadata nests %d levels deep, more than the %d "
             "allowed" % (depth, MAX_JSON_DEPTH))
        try:
            number = _json_number(float)
            self.metadata = json.loads(meta.decode("utf-8-sig"), parse_constant=number,
                                       parse_float=number, parse_int=_json_number(int))
            json.dumps(self.metadata, ensure_ascii=False).encode("utf-8")  # no lone \ud800
        except (ValueError, RecursionError):  # UnicodeError and JSONDecodeError among them
            raise self._fail("header metadata is not valid JSON") from None
        need(isinstance(self.metadata, dict), "header metadata is not a JSON object")
        # The index, which ends the file, and its checksum (readIndexBytes).
        need(header_size <= index_offset <= size,
             "index offset %d outside the file (%d bytes)" % (index_offset, size))
        need(count <= (size - index_offset) // 40,
             "truncated: the index of %d frames does not fit in the file" % count)
        implied = index_offset + 40 * count + 8
        need(size == implied, "%s: %d bytes, the header implies %d"
             % ("truncated" if size < implied else "trailing data", size, implied))
        entries = d[index_offset:size - 8]
        need(xxh3(entries) == struct.unpack_from("<Q", d, size - 8)[0],
             "frame index checksum mismatch (index damaged)")
        self.index = [ENTRY.unpack_from(entries, 40 * i) for i in range(count)]
        # Each entry, and the frames tiling header .. index in order (decodeIndex).
        end = header_size
        for i, (offset, csize, rsize, ns, nsp, _) in enumerate(self.index):
            expect = ns * 8 + nsp * 16 if self.encoding == 0 else ns * 4 + nsp * 12
            need(rsize == expect, "raw size %d disagrees with %d surface and %d splash particles "
                 "(%d bytes)" % (rsize, ns, nsp, expect), i)
            need(rsize <= MAX_RAW_FRAME,
                 "raw size %d bytes exceeds the 256 MiB frame limit" % rsize, i)
            bound = rsize + (rsize >> 8) + ((131072 - rsize) >> 11 if rsize < 131072 else 0)
            need(0 < csize <= bound,  # ZSTD_compressBound
                 "compressed size %d impossible for raw size %d" % (csize, rsize), i)
            need(rsize <= (1 << 20) + 1024 * csize, "raw size %d from %d compressed bytes is beyond"
                 " the format's bound of 1 MiB + 1024 x the compressed size" % (rsize, csize), i)
            need(offset + csize <= index_offset, "offset %d + size %d extends past the frame data "
                 "(ends at %d)" % (offset, csize, index_offset), i)
            need(offset >= end, "overlaps frame %d" % (i - 1) if i else "starts inside the header",
                 i)
            need(offset <= end, "unaccounted gap of %d bytes before the frame" % (offset - end), i)
            end = offset + csize
        need(end == index_offset,
             "%d unaccounted bytes between the last frame and the index" % (index_offset - end))

    def _fail(self, what, frame=None):
        where = "" if frame is None else "frame %d: " % frame
        return CacheError("%s: %s%s" % (self.path, where, what))

    def _need(self, ok, what, frame=None):
        if not ok:
            raise self._fail(what, frame)

    def __len__(self):
        return len(self.index)

    def frame(self, i):
        """(surface [(x, y)], splash [(x, y, vx, vy)]) of frame i, decoded and checksummed as
        Reader::readFrame does (values not checked: see verify)."""
        offset, csize, rsize, ns, nsp, checksum = self.index[i]
        data = self.data[offset:offset + csize]
        try:
            stated = zstandard.get_frame_parameters(data).content_size
        except zstandard.ZstdError:
            raise self._fail("compressed data is not a zstd frame", i) from None
        self._need(stated == rsize, "zstd content size disagrees with the index (%d bytes "
                   "expected)" % rsize, i)
        z = zstandard.ZstdDecompressor(max_window_size=1 << 31).decompressobj()
        try:
            raw = z.decompress(data)
        except zstandard.ZstdError as e:
            why = re.sub(r"^zstd \w+ error: ", "", str(e))
            raise self._fail("decompression failed: " + why, i) from None
        self._need(z.eof and not z.unused_data, "decompression failed: " + (
            "%d bytes after the zstd frame" % len(z.unused_data) if z.eof else "truncated"), i)
        self._need(len(raw) == rsize,
                   "decompressed to %d bytes, index says %d" % (len(raw), rsize), i)
        rec = _unfilter(raw, self.encoding, ns, nsp, self.flags)
        self._need(xxh3(rec) == checksum, "checksum mismatch (data damaged)", i)
        if self.encoding == 0:
            s = struct.unpack_from("<%df" % (2 * ns), rec, 0)
            p = struct.unpack_from("<%df" % (4 * nsp), rec, 8 * ns)
            return list(zip(s[0::2], s[1::2])), list(zip(p[0::4], p[1::4], p[2::4], p[3::4]))
        x0, y0, x1, y1 = self.domain
        # Same arithmetic as the C++ reader: double, then rounded to float32.
        qx = lambda q: _f32(x0 + (x1 - x0) * (q / 65535.0))
        qy = lambda q: _f32(y0 + (y1 - y0) * (q / 65535.0))
        s = struct.unpack_from("<%dH" % (2 * ns), rec, 0)
        pp = struct.unpack_from("<%dH" % (2 * nsp), rec, 4 * ns)
        pv = struct.unpack_from("<%df" % (2 * nsp), rec, 4 * ns + 4 * nsp)
        surface = [(qx(a), qy(b)) for a, b in zip(s[0::2], s[1::2])]
        splash = [(qx(a), qy(b), u, v) for a, b, u, v in zip(pp[0::2], pp[1::2], pv[0::2], pv[1::2])]
        return surface, splash

    def verify(self):
        """Decodes every frame; refuses a NaN or infinity and a position outside the header's
        domain, bounds included (swell-cache verify). Returns the number of particles."""
        x0, y0, x1, y1 = self.domain
        particles = 0
        for i in range(len(self)):
            surface, splash = self.frame(i)
            particles += len(surface) + len(splash)
            self._need(all(math.isfinite(v) for p in surface + splash for v in p),
                       "holds a non-finite value (NaN or infinity)", i)
            for kind, points in (("surface", surface), ("splash", splash)):
                for k, (x, y) in enumerate(p[:2] for p in points):
                    if not (x0 <= x <= x1 and y0 <= y <= y1):
                        raise self._fail("%s particle %d at (%s, %s) is outside the header's domain"
                                         " x %s .. %s, y %s .. %s" % ((kind, k) + tuple(
                                             map(_f32_text, (x, y, x0, x1, y0, y1)))), i)
        return particles


def main(argv):
    usage = "usage: swell_cache.py CACHE [--frame N]"
    if len(argv) not in (2, 4) or (len(argv) == 4 and argv[2] != "--frame"):
        print("swell_cache.py: " + usage, file=sys.stderr)
        return 2
    if len(argv) == 4 and not re.fullmatch(r"[0-9]{1,19}", argv[3]):
        print("swell_cache.py: --frame %r is not a frame number (0 first); %s" % (argv[3], usage),
              file=sys.stderr)
        return 2
    path = argv[1]
    try:
        c = Cache(path)
        if len(argv) == 2:
            particles = c.verify()
            counts = [e[3] for e in c.index]
            print(json.dumps({"version": c.version, "frames": len(c), "dt": c.dt,
                              "frame_interval": c.frame_interval, "seed": c.seed,
                              "surface_max": max(counts, default=0), "particles": particles,
                              "checksums": "checked"}))
            return 0
        i = int(argv[3])
        c._need(i < len(c), "frame %d does not exist (the cache has %d)" % (i, len(c)))
        surface, splash = c.frame(i)
        sys.stdout.write("".join(["kind,x,y,vx,vy\n"] + ["surface,%.9g,%.9g,,\n" % p for p in
                                 surface] + ["splash,%.9g,%.9g,%.9g,%.9g\n" % p for p in splash]))
        return 0
    except (CacheError, OSError, ValueError, struct.error, zstandard.ZstdError, IndexError,
            KeyError, OverflowError, MemoryError, RecursionError) as e:
        what = str(e) if isinstance(e, CacheError) else "%s: %s" % (path, str(e) or type(e).__name__)
        print("swell_cache.py: " + re.sub(r"[\r\n]+", " ", what), file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
