#!/bin/sh
# The installed library as other projects use it: `cmake --install` to a
# temporary prefix, then
# - the header alone compiles as C89;
# - a C program built with pkg-config against the shared library decodes
#   both conformance suites as an external decoder (decode.c);
# - a C-only CMake project built with find_package(m4mesh) against the
#   static library decodes the 3D suite (c/: the package brings the C++
#   runtime);
# - a C++ project built with find_package(m4mesh) against the static
#   library encodes a sequence with every codec and decodes it back
#   (cxx/encode_decode.cc);
# - the installed tool finds the installed suite (conform without a
#   folder) and the installed site (serve), from any folder.
# Usage: test.sh BUILD_DIR SOURCE_DIR C_COMPILER CXX_COMPILER
set -eu
build=$1 source=$2 cc=$3 cxx=$4
prefix=$(mktemp -d)
trap 'rm -rf "$prefix"' EXIT
cmake --install "$build" --prefix "$prefix/usr" > "$prefix/install.log"
lib=$(dirname "$(find "$prefix/usr" -name libm4mesh.a)")
export PKG_CONFIG_PATH="$lib/pkgconfig"

printf '#include <m4mesh.h>\n' | "$cc" -std=c89 -pedantic -Wall -Wextra -Werror -fsyntax-only $(pkg-config --cflags m4mesh) -x c -
# shellcheck disable=SC2046
"$cc" -std=c99 -pedantic -Wall -Wextra -Werror -o "$prefix/decode" "$source/tests/install/decode.c" \
  $(pkg-config --cflags --libs m4mesh) -Wl,-rpath,"$lib"
"$prefix/usr/bin/m4mesh" conform "$source/conformance" --decoder "'$prefix/decode' --method {method} {in} {out}" > "$prefix/2d.log" ||
  { cat "$prefix/2d.log"; exit 1; }
tail -n 1 "$prefix/2d.log"
"$prefix/usr/bin/m4mesh" conform "$source/conformance/mesh3d" --decoder "'$prefix/decode' --chunk 13 {in} {out}" > "$prefix/3d.log" ||
  { cat "$prefix/3d.log"; exit 1; }
tail -n 1 "$prefix/3d.log"

cmake -S "$source/tests/install/cxx" -B "$prefix/cxx" -DCMAKE_PREFIX_PATH="$prefix/usr" -DCMAKE_CXX_COMPILER="$cxx" > "$prefix/cxx.log"
cmake --build "$prefix/cxx" >> "$prefix/cxx.log"
"$prefix/cxx/encode_decode"

cmake -S "$source/tests/install/c" -B "$prefix/c" -DCMAKE_PREFIX_PATH="$prefix/usr" -DCMAKE_C_COMPILER="$cc" > "$prefix/c.log"
cmake --build "$prefix/c" >> "$prefix/c.log"
"$prefix/usr/bin/m4mesh" conform "$source/conformance/mesh3d" --decoder "'$prefix/c/decode' {in} {out}" > "$prefix/3d-static.log" ||
  { cat "$prefix/3d-static.log"; exit 1; }
echo "C-only project, static library: $(tail -n 1 "$prefix/3d-static.log")"

cd "$prefix"
"$prefix/usr/bin/m4mesh" conform > "$prefix/installed-suite.log" 2>&1 || { cat "$prefix/installed-suite.log"; exit 1; }
grep -q "usr/share/m4mesh/conformance" "$prefix/installed-suite.log" || { echo "conform did not take the installed suite:"; cat "$prefix/installed-suite.log"; exit 1; }
if [ -f "$prefix/usr/share/m4mesh/site/index.html" ]; then
  "$prefix/usr/bin/m4mesh" serve --port 0 > "$prefix/serve.log" 2>&1 &
  server=$!
  for _ in $(seq 100); do grep -q "http://" "$prefix/serve.log" && break; sleep 0.1; done
  address=$(grep -o "http://[0-9.:]*" "$prefix/serve.log" | head -n 1)
  python3 -c "import sys, urllib.request; page = urllib.request.urlopen(sys.argv[1]).read(); sys.exit(0 if b'<html' in page.lower() else 1)" "$address/" ||
    { kill "$server"; echo "serve: no page from the installed site at '$address'"; cat "$prefix/serve.log"; exit 1; }
  kill "$server"
  echo "serve: the installed site at $address"
fi
