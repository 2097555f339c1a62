#!/usr/bin/env bash
# The Python example reader of docs/cache-format.md (tools/swell_cache.py) reads files
# that swell writes, value for value, in both encodings; and it notices damage.
set -euo pipefail
bin=$1 reader=$2 py=$3
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
for enc in float32 quantized16; do
    "$bin/swell-cache" synth "$dir/$enc.swell" --frames 6 --surface 37 --splash 5 --encoding $enc 2>/dev/null
    "$py" "$reader" "$dir/$enc.swell" | grep -q '"checksums": "checked"'
    for f in 0 5; do
        "$py" "$reader" "$dir/$enc.swell" --frame $f > "$dir/py.csv"
        "$bin/swell-cache" dump "$dir/$enc.swell" --frame $f > "$dir/cc.csv"
        cmp "$dir/py.csv" "$dir/cc.csv"
    done
done
# A flipped byte in the last frame's data must be reported, not read.
size=$(stat -c %s "$dir/float32.swell")
printf '\xff' | dd of="$dir/float32.swell" bs=1 seek=$((size - 6 * 40 - 8 - 3)) conv=notrunc 2>/dev/null
if "$py" "$reader" "$dir/float32.swell" 2>/dev/null; then echo "damage not detected"; exit 1; fi
# A writer's temporary (OUT.tmp-PID) is refused as by swell-cache verify, naming the writer.
cp "$dir/quantized16.swell" "$dir/q.swell.tmp-999999999"
if "$py" "$reader" "$dir/q.swell.tmp-999999999" 2> "$dir/err"; then echo "temporary read"; exit 1; fi
grep -q "a temporary file of an unfinished write by process 999999999 (no longer running" "$dir/err" ||
    { echo "temporary message: $(cat "$dir/err")"; exit 1; }
echo "python reader OK"
