#!/usr/bin/env bash
# The Python example reader of docs/cache-format.md (tools/swell_cache.py) reads files
# that swell writes, value for value, in both encodings; and it refuses what the C++ reader
# (swell-cache verify) refuses, in the same words, each refusal one line on stderr.
set -euo pipefail
bin=$1 reader=$2 py=$3
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
for enc in float32 quantized16; do
    "$bin/swell-cache" synth "$dir/$enc.swell" --frames 6 --surface 37 --splash 5 --encoding $enc 2>/dev/null
    "$py" "$reader" "$dir/$enc.swell" | grep -q '"checksums": "checked"'
    for f in 0 5; do
        "$py" "$reader" "$dir/$enc.swell" --frame $f > "$dir/py.csv"
        "$bin/swell-cache" dump "$dir/$enc.swell" --frame $f > "$dir/cc.csv"
        cmp "$dir/py.csv" "$dir/cc.csv"
    done
done
"$bin/swell-cache" synth "$dir/plain.swell" --frames 6 --surface 37 --splash 5 --no-shuffle --no-delta 2>/dev/null

# Damaged files, made with the same python (python3-zstandard, python3-xxhash).
cat > "$dir/craft.py" <<'PY'
"""craft.py CASE IN OUT [ARG]: a damaged copy of cache IN, checksums recomputed where said."""
import random
import struct
import sys

import xxhash
import zstandard

H = struct.Struct("<IIII4fdIIQfIQQQ")  # the fixed header from offset 8
E = struct.Struct("<QQQIIQ")
xxh3 = xxhash.xxh3_64_intdigest


def build(h, meta, frames):
    """A file whose sizes, offsets and checksums all agree: header fields h (from offset 8),
    metadata, frames [(zstd bytes, raw size, ns, nsp, record checksum)]."""
    h = list(h)
    h[1], h[13], h[14], h[15] = 96 + len(meta), len(meta), len(frames), 96 + len(meta)
    body, entries = b"", b""
    for z, raw, ns, nsp, s in frames:
        entries += E.pack(h[15], len(z), raw, ns, nsp, s)
        body += z
        h[15] += len(z)
    head = b"\x89SWL\r\n\x1a\n" + H.pack(*h)[:80]
    head += struct.pack("<Q", xxh3(head + meta)) + meta
    return head + body + entries + struct.pack("<Q", xxh3(entries))


def refix(d):
    """Recomputes the header and index checksums wherever the (damaged) header puts them."""
    h = H.unpack_from(d, 8)
    if 96 + h[13] <= len(d):
        d = d[:88] + struct.pack("<Q", xxh3(d[:88] + d[96:96 + h[13]])) + d[96:]
    end = h[15] + 40 * h[14]
    return d[:end] + struct.pack("<Q", xxh3(d[h[15]:end])) + d[end + 8:] if end + 8 <= len(d) else d


def frame(rec, ns, nsp):  # a frame of the unfiltered record `rec`
    return zstandard.ZstdCompressor().compress(rec), len(rec), ns, nsp, xxh3(rec)


def main(case, src, out, arg="0"):
    d = open(src, "rb").read()
    h = H.unpack_from(d, 8)
    o = h[15]  # index offset
    index = [E.unpack_from(d, o + 40 * i) for i in range(h[14])]
    frames = [(d[e[0]:e[0] + e[1]],) + e[2:] for e in index]
    meta = d[96:h[1]]
    rng = random.Random(arg)
    if case == "swap":  # index entries 1 and 2 exchanged (and the index checksum recomputed)
        d = d[:o + 40] + d[o + 80:o + 120] + d[o + 40:o + 80] + d[o + 120:]
        d = refix(d) if arg == "refix" else d
    elif case == "index-checksum":
        d = d[:-3] + bytes([d[-3] ^ 0x40]) + d[-2:]
    elif case == "deep-metadata":
        d = build(h, b"[" * 1000000 + b"]" * 1000000, frames)
    elif case == "zeros":  # one frame of ARG bytes of zeros, a few dozen compressed
        d = build(h, meta, [frame(bytes(int(arg)), int(arg) // 8, 0)])
    elif case in ("outside", "nan"):  # frame 2 of an unfiltered float32 cache
        rec = bytearray(zstandard.ZstdDecompressor().decompress(frames[2][0]))
        if case == "outside":  # surface particle 3 at x_max + 0.5
            struct.pack_into("<f", rec, 8 * 3, h[6] + 0.5)
        else:  # splash particle 0's vx
            struct.pack_into("<f", rec, 8 * frames[2][2] + 8, float("nan"))
        frames[2] = frame(bytes(rec), *frames[2][2:4])
        d = build(h, meta, frames)
    elif case == "refixed":  # 1-2 bits of the checked header fields or index flipped, sums redone
        where = [*range(8, 24), *range(68, 88), *range(o, len(d) - 8)]
        b = bytearray(d)
        for p in rng.sample(where, rng.randint(1, 2)):
            b[p] ^= 1 << rng.randrange(8)
        d = refix(bytes(b))
    elif case == "random":  # flipped bits anywhere, a truncation, or junk appended
        kind = rng.choice(["flip", "flip", "flip", "truncate", "junk"])
        if kind == "flip":  # not in a zstd frame header descriptor: decoders ignore its bit 4
            b, descriptor = bytearray(d), {e[0] + 4 for e in index}
            for p in rng.sample([p for p in range(len(d)) if p not in descriptor], rng.randint(1, 3)):
                b[p] ^= 1 << rng.randrange(8)
            d = bytes(b)
        elif kind == "truncate":
            d = d[:rng.randrange(len(d))]
        else:
            d += bytes(rng.randrange(256) for _ in range(rng.randint(1, 50)))
    else:
        sys.exit("craft.py: unknown case " + case)
    open(out, "wb").write(d)


if __name__ == "__main__":
    main(*sys.argv[1:])
PY
craft() { "$py" "$dir/craft.py" "$@"; }

# The Python reader exits STATUS on ARGS with exactly one line on stderr (in $dir/err).
py_fails() {
    local status=$1 rc=0
    shift
    "$py" "$reader" "$@" > /dev/null 2> "$dir/err" || rc=$?
    [ "$rc" = "$status" ] || fail "$* exits $rc, not $status: $(cat "$dir/err")"
    [ "$(wc -l < "$dir/err")" = 1 ] || fail "$* does not print one line: $(cat "$dir/err")"
    ! grep -q Traceback "$dir/err" || fail "$* prints a traceback"
}
# Both readers refuse FILE in the same words, which contain WORDS.
both_refuse() {
    local file=$1 words=$2
    py_fails 1 "$file"
    if "$bin/swell-cache" verify "$file" > /dev/null 2> "$dir/cerr"; then
        fail "swell-cache verify accepts $file"
    fi
    local py_says cc_says
    py_says=$(sed 's/^swell_cache.py: //' "$dir/err") cc_says=$(sed 's/^swell-cache: //' "$dir/cerr")
    [ "$py_says" = "$cc_says" ] || fail "the readers disagree on $file: '$py_says' vs '$cc_says'"
    grep -qF -- "$words" "$dir/err" || fail "$file: '$words' not in: $py_says"
}

# A flipped byte in the last frame's data must be reported, not read.
cp "$dir/float32.swell" "$dir/flip.swell"
size=$(stat -c %s "$dir/flip.swell")
printf '\xff' | dd of="$dir/flip.swell" bs=1 seek=$((size - 6 * 40 - 8 - 3)) conv=notrunc 2>/dev/null
py_fails 1 "$dir/flip.swell"
# Two index entries exchanged: the index checksum says so; with it recomputed, the frames no
# longer follow each other (they would otherwise decode as each other's frames).
craft swap "$dir/float32.swell" "$dir/swap.swell"
both_refuse "$dir/swap.swell" "frame index checksum mismatch (index damaged)"
craft swap "$dir/float32.swell" "$dir/swap2.swell" refix
both_refuse "$dir/swap2.swell" "frame 1: unaccounted gap of"
craft index-checksum "$dir/float32.swell" "$dir/sum.swell"
both_refuse "$dir/sum.swell" "frame index checksum mismatch (index damaged)"
# Metadata nested 1,000,000 deep, its checksum right: refused before it is parsed.
craft deep-metadata "$dir/float32.swell" "$dir/deep.swell"
both_refuse "$dir/deep.swell" "header metadata nests 1000000 levels deep, more than the 64 allowed"
# 2 MiB + 8000 raw bytes of zeros from a few dozen compressed: beyond 1 MiB + 1024 x; refused
# by both readers when opened, before decoding. 1 MiB of zeros is within the bound and read.
craft zeros "$dir/float32.swell" "$dir/zeros.swell" $((2 * 1024 * 1024 + 8000))
both_refuse "$dir/zeros.swell" "frame 0: raw size 2105152 from "
py_fails 1 "$dir/zeros.swell" --frame 0
bound="beyond the format's bound of 1 MiB \+ 1024 x the compressed size"
grep -qE "frame 0: raw size 2105152 from [0-9]+ compressed bytes is $bound" "$dir/err" ||
    fail "ratio bound: $(cat "$dir/err")"
craft zeros "$dir/float32.swell" "$dir/mib.swell" $((1024 * 1024))
"$py" "$reader" "$dir/mib.swell" --frame 0 > /dev/null
# A position outside the domain and a NaN: verify-level checks, so refused by the summary
# (swell-cache verify), while one frame still reads (--frame N, swell-cache dump).
craft outside "$dir/plain.swell" "$dir/outside.swell"
both_refuse "$dir/outside.swell" "frame 2: surface particle 3 at (4.7, "
craft nan "$dir/plain.swell" "$dir/nan.swell"
both_refuse "$dir/nan.swell" "frame 2: holds a non-finite value (NaN or infinity)"
for f in outside nan; do
    "$py" "$reader" "$dir/$f.swell" --frame 2 > "$dir/py.csv"
    "$bin/swell-cache" dump "$dir/$f.swell" --frame 2 > "$dir/cc.csv"
    cmp "$dir/py.csv" "$dir/cc.csv"
done
# 40 randomly damaged variants: each refused by both readers, in one line, no traceback.
for seed in $(seq 1 40); do
    case $((seed % 4)) in
        0) craft random "$dir/float32.swell" "$dir/r.swell" $seed ;;
        1) craft random "$dir/quantized16.swell" "$dir/r.swell" $seed ;;
        2) craft refixed "$dir/float32.swell" "$dir/r.swell" $seed ;;
        3) craft refixed "$dir/quantized16.swell" "$dir/r.swell" $seed ;;
    esac
    py_fails 1 "$dir/r.swell"
    if "$bin/swell-cache" verify "$dir/r.swell" > /dev/null 2>&1; then
        fail "variant $seed: swell-cache accepts what the Python reader refuses: $(cat "$dir/err")"
    fi
done
# Bad command lines and frame numbers; a missing file; python3-xxhash missing.
py_fails 2
py_fails 2 "$dir/float32.swell" --frame
py_fails 2 "$dir/float32.swell" --frame abc
py_fails 2 "$dir/float32.swell" --frame -1
py_fails 1 "$dir/float32.swell" --frame 6
grep -q "frame 6 does not exist (the cache has 6)" "$dir/err" || fail "frame 6: $(cat "$dir/err")"
py_fails 1 "$dir/missing.swell"
grep -q "missing.swell: cannot open: No such file or directory" "$dir/err" || fail "missing: $(cat "$dir/err")"
mkdir "$dir/no-xxhash"
echo 'raise ModuleNotFoundError("No module named xxhash", name="xxhash")' > "$dir/no-xxhash/xxhash.py"
rc=0
PYTHONPATH="$dir/no-xxhash" "$py" "$reader" "$dir/float32.swell" > /dev/null 2> "$dir/err" || rc=$?
[ "$rc" != 0 ] && [ "$(wc -l < "$dir/err")" = 1 ] && grep -q "install python3-xxhash" "$dir/err" ||
    fail "xxhash missing: $rc $(cat "$dir/err")"
# A writer's temporary (OUT.tmp-PID) is refused as by swell-cache verify, naming the writer.
cp "$dir/quantized16.swell" "$dir/q.swell.tmp-999999999"
py_fails 1 "$dir/q.swell.tmp-999999999"
grep -q "a temporary file of an unfinished write by process 999999999 (no longer running" "$dir/err" ||
    { echo "temporary message: $(cat "$dir/err")"; exit 1; }
echo "python reader OK"
