#!/usr/bin/env bash
# swell-cache end to end: synth -> info/verify/dump succeed; damage, a missing file and
# bad arguments give one clear stderr line and a non-zero exit.
set -euo pipefail
bin=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

"$bin/swell-cache" synth "$dir/a.swell" --frames 20 --surface 50 --splash 2 2>/dev/null
"$bin/swell-cache" verify "$dir/a.swell" | grep -q "OK, 20 frames" || fail "verify output"
"$bin/swell-cache" info "$dir/a.swell" --json > "$dir/info.json"
grep -q '"frames":20' "$dir/info.json" || fail "info --json frames"
grep -q '"surface_mean":50' "$dir/info.json" || fail "info --json surface_mean"
grep -q '"splash_frames":20' "$dir/info.json" || fail "info --json splash_frames"
grep -q '"splash_median":2.0' "$dir/info.json" || fail "info --json splash_median"
"$bin/swell-cache" synth "$dir/dry.swell" --frames 7 --surface 50 --splash 0 2>/dev/null
"$bin/swell-cache" info "$dir/dry.swell" | grep -q "^splash particles   mean 0.0, max 0, median 0; in 0 of 7 frames" ||
    fail "info splash line: $("$bin/swell-cache" info "$dir/dry.swell" | grep splash)"
[[ $("$bin/swell-cache" dump "$dir/a.swell" --frame 19 | wc -l) -eq 53 ]] || fail "dump rows"
# Positions outside the header's domain break the format's rule: verify refuses them. The
# header's domain is narrowed to x 0 .. 1 m and its checksum recomputed (XXH3-64 of the fixed
# header before the checksum field and the metadata).
/usr/bin/python3 - "$dir/a.swell" "$dir/narrow.swell" <<'PY' || fail "narrowing the domain"
import struct, sys, xxhash
b = bytearray(open(sys.argv[1], "rb").read())
struct.pack_into("<f", b, 32, 1.0)  # x max (domain at byte 24: x min, y min, x max, y max)
meta = struct.unpack_from("<I", b, 68)[0]
h = xxhash.xxh3_64()
h.update(bytes(b[:88]))
h.update(bytes(b[96:96 + meta]))
struct.pack_into("<Q", b, 88, h.intdigest())
open(sys.argv[2], "wb").write(b)
PY
if out=$("$bin/swell-cache" verify "$dir/narrow.swell" 2>&1); then fail "verify accepted positions outside the domain"; fi
grep -q "is outside the header's domain x .* \.\. 1, y" <<<"$out" || fail "verify domain message: $out"
# A synthetic cache larger than the disk is refused at once (exit 2), naming OUT and what fits.
rc=0
out=$("$bin/swell-cache" synth "$dir/huge.swell" --frames 1000000 --surface 10000000 2>&1) || rc=$?
[[ $rc -eq 2 ]] || fail "synth beyond the disk: exit $rc: $out"
grep -q "GB free: about .* frames fit" <<<"$out" || fail "synth beyond the disk message: $out"
[[ ! -e "$dir/huge.swell" ]] || fail "synth beyond the disk left a file"
# A damaged cache exits 4 (README "Exit statuses").
rc=0
"$bin/swell-cache" verify "$dir/narrow.swell" > /dev/null 2>&1 || rc=$?
[[ $rc -eq 4 ]] || fail "verify of a damaged cache: exit $rc, not 4"
# A negative frame is refused naming the option, not wrapped to 2^64 - 1.
if out=$("$bin/swell-cache" dump "$dir/a.swell" --frame -1 2>&1); then fail "dump --frame -1 accepted"; fi
grep -q -- "--frame" <<<"$out" || fail "dump --frame -1 message: $out"
grep -q "18446744073709551615" <<<"$out" && fail "dump --frame -1 wrapped: $out"
# synth caches carry the bake's "replay" block (water extent, steady start); info prints it.
grep -q '"replay":{"particle_spacing":0.0816326530612244[0-9]*,"steady_reason":"synthetic travelling wave: steady from the start","steady_start_s":0.0,"still_water_level":0.5,"water_x_max":4.0,"water_x_min":0.0}' "$dir/info.json" ||
    fail "info --json replay block: $(grep -o '"replay":{[^}]*}' "$dir/info.json")"
"$bin/swell-cache" info "$dir/a.swell" > "$dir/info.txt"
grep -q "^water extent       x 0 .. 4 m, still water at y = 0.5 m" "$dir/info.txt" || fail "info water extent"
grep -q "^steady from        0 s (synthetic travelling wave: steady from the start)" "$dir/info.txt" ||
    fail "info steady start: $(cat "$dir/info.txt")"

# recode: the same frames in quantized16, within the header's position error; refused
# encodings leave nothing behind.
"$bin/swell-cache" recode "$dir/a.swell" "$dir/q.swell" --encoding quantized16 2>/dev/null
"$bin/swell-cache" verify "$dir/q.swell" --json | grep -q '"nonfinite":0' || fail "recode verify"
"$bin/swell-cache" info "$dir/q.swell" --json > "$dir/qinfo.json"
grep -q '"encoding":"quantized16"' "$dir/qinfo.json" || fail "recode encoding"
grep -q '"frames":20' "$dir/qinfo.json" || fail "recode frames"
err=$(grep -o '"max_position_error_m":[0-9.e-]*' "$dir/qinfo.json" | cut -d: -f2)
paste -d, <("$bin/swell-cache" dump "$dir/a.swell" --frame 7 | tail -n +2) \
          <("$bin/swell-cache" dump "$dir/q.swell" --frame 7 | tail -n +2) |
    awk -F, -v e="$err" '{ d = $2 - $7; if (d < 0) d = -d; if (d > e * 1.0001 + 1e-9) bad = 1 }
                         END { exit bad }' || fail "recode error above max_position_error_m $err"
if "$bin/swell-cache" recode "$dir/a.swell" "$dir/z.swell" --encoding int8 2>/dev/null; then
    fail "recode accepted --encoding int8"
fi
[[ ! -e "$dir/z.swell" ]] || fail "a refused recode left a file"

# Damage in the middle of the frame data: verify must fail and name file and frame.
cp "$dir/a.swell" "$dir/bad.swell"
size=$(stat -c %s "$dir/bad.swell")
printf '\x00\x00\x00\x00' | dd of="$dir/bad.swell" bs=1 seek=$((size / 2)) conv=notrunc 2>/dev/null
if "$bin/swell-cache" verify "$dir/bad.swell" 2> "$dir/err"; then fail "verify passed a damaged file"; fi
[[ $(wc -l < "$dir/err") -eq 1 ]] || fail "error is not one line: $(cat "$dir/err")"
grep -q "bad.swell: frame [0-9]*:" "$dir/err" || fail "error does not name file and frame: $(cat "$dir/err")"

# Truncated: refused at open.
head -c $((size - 1)) "$dir/a.swell" > "$dir/trunc.swell"
if "$bin/swell-cache" info "$dir/trunc.swell" 2> "$dir/err"; then fail "info passed a truncated file"; fi
grep -q "trunc.swell: truncated" "$dir/err" || fail "truncation message: $(cat "$dir/err")"

if "$bin/swell-cache" verify "$dir/missing.swell" 2> "$dir/err"; then fail "missing file accepted"; fi
grep -q "missing.swell: cannot open" "$dir/err" || fail "missing-file message"
if "$bin/swell-cache" dump "$dir/a.swell" --frame 20 2> "$dir/err"; then fail "frame 20 accepted"; fi
if "$bin/swell-cache" synth "$dir/x.swell" --frames 0 2>/dev/null; then fail "--frames 0 accepted"; fi
[[ ! -e "$dir/x.swell" ]] || fail "a refused synth left a file"
# A temporary file (what a writer killed with SIGKILL leaves, even a complete one that was
# never renamed) is refused, naming the writer's PID, whether it is still running or not.
cp "$dir/a.swell" "$dir/a.swell.tmp-999999999"
if "$bin/swell-cache" verify "$dir/a.swell.tmp-999999999" 2> "$dir/err"; then fail "verify passed a temporary file"; fi
[[ $(wc -l < "$dir/err") -eq 1 ]] || fail "error is not one line: $(cat "$dir/err")"
grep -q "a.swell.tmp-999999999: a temporary file of an unfinished write by process 999999999 (no longer running" "$dir/err" ||
    fail "temporary-file message: $(cat "$dir/err")"
cp "$dir/a.swell" "$dir/a.swell.tmp-$$"
if "$bin/swell-cache" verify "$dir/a.swell.tmp-$$" 2> "$dir/err"; then fail "verify passed a live writer's temporary"; fi
grep -q "by process $$ (still running)" "$dir/err" || fail "live temporary message: $(cat "$dir/err")"
# synth and recode take the output lock as swell-bake does: with another process holding it
# (a POSIX record lock on OUT.lock, as fcntl F_SETLK takes it), exit 6 naming that process.
python3 -c 'import fcntl, sys, time; f = open(sys.argv[1], "a"); fcntl.lockf(f, fcntl.LOCK_EX); print(flush=True); time.sleep(60)' \
    "$dir/held.swell.lock" > "$dir/holder.out" &
holder=$!
for _ in $(seq 100); do [[ -s "$dir/holder.out" ]] && break; sleep 0.05; done
set +e
"$bin/swell-cache" synth "$dir/held.swell" --frames 5 2> "$dir/err"; synth_rc=$?
"$bin/swell-cache" recode "$dir/a.swell" "$dir/held.swell" 2> "$dir/err2"; recode_rc=$?
set -e
kill "$holder"
[[ $synth_rc -eq 6 && $recode_rc -eq 6 ]] || fail "a held output: synth exit $synth_rc, recode exit $recode_rc"
grep -q "in use by process $holder" "$dir/err" || fail "held-output message: $(cat "$dir/err")"
grep -q "in use by process $holder" "$dir/err2" || fail "held-output message: $(cat "$dir/err2")"
[[ ! -e "$dir/held.swell" ]] || fail "a refused synth wrote the output"
echo "swell-cache CLI OK"
