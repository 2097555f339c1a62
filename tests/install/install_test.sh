#!/usr/bin/env bash
# cmake --install into a temporary prefix, then build examples/consumer against it (CMake
# package) and examples/consumer/heights.c with pkg-config alone, and run them on a synthetic
# cache made by the installed swell-cache: the C and C++ consumers must print the same replay.
#   install_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1
src=$2
tmp=$(mktemp -d "${TMPDIR:-/tmp}/swell_install_XXXXXX")
trap 'rm -rf "$tmp"' EXIT
prefix=$tmp/prefix

cmake --install "$build" --prefix "$prefix" >/dev/null
for f in lib/cmake/swell/swellConfig.cmake lib/cmake/swell/swellConfigVersion.cmake \
         lib/cmake/swell/swellTargets.cmake lib/libswell.so lib/libswell_runtime.a \
         lib/pkgconfig/swell.pc include/swell/swell.h include/swell/runtime/playback.h \
         bin/swell-bake bin/swell-play bin/swell-cache share/doc/swell/README.md \
         share/swell/scenes/surging.json; do
    [[ -e "$prefix/$f" ]] || { echo "install_test: $prefix/$f was not installed" >&2; exit 1; }
done
# libswell exports the C API and nothing of the C++ libraries inside it (namespace swell::
# mangles as 5swell; libstdc++'s unique template statics cannot be hidden and are allowed).
symbols=$(nm -D --defined-only "$prefix/lib/libswell.so" | awk '{print $3}')
grep -qx swell_replay_create <<<"$symbols" || { echo "install_test: libswell.so lacks swell_replay_create" >&2; exit 1; }
if grep -q '5swell' <<<"$symbols"; then
    echo "install_test: libswell.so exports C++ symbols of swell:" >&2
    grep '5swell' <<<"$symbols" | head >&2
    exit 1
fi

cmake -S "$src/examples/consumer" -B "$tmp/consumer" -G Ninja -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_PREFIX_PATH="$prefix" >/dev/null
cmake --build "$tmp/consumer" >/dev/null

"$prefix/bin/swell-cache" synth "$tmp/wave.swell" --frames 200 --surface 400 --splash 2 >/dev/null
"$tmp/consumer/heights_c" "$tmp/wave.swell" 5 >"$tmp/c.txt"
"$tmp/consumer/heights_cpp" "$tmp/wave.swell" 5 >"$tmp/cpp.txt"
[[ $(wc -l <"$tmp/c.txt") -eq 10 ]] || { echo "install_test: heights_c printed:" >&2; cat "$tmp/c.txt" >&2; exit 1; }
diff "$tmp/c.txt" "$tmp/cpp.txt" || { echo "install_test: the C and C++ consumers differ" >&2; exit 1; }

# pkg-config alone, as a Makefile project would use it.
export PKG_CONFIG_PATH=$prefix/lib/pkgconfig
cc -std=c99 -Wall -Werror "$src/examples/consumer/heights.c" -o "$tmp/heights_pc" \
    $(pkg-config --cflags --libs swell) -Wl,-rpath,"$(pkg-config --variable=libdir swell)"
"$tmp/heights_pc" "$tmp/wave.swell" 5 >"$tmp/pc.txt"
diff "$tmp/c.txt" "$tmp/pc.txt"
echo "install_test: installed, consumers built with CMake and pkg-config, same replay"
head -2 "$tmp/c.txt"
