#!/usr/bin/env bash
# Build the browser explorer into web/dist/ (static files any static host can serve): the core
# library (src/, without src/io and src/paper) compiled to WebAssembly with Emscripten (Debian's
# emscripten package), the Embind bindings (web/src/bindings.cpp), the page (web/src/) and the
# plotting library uPlot from web/node_modules (npm ci, from web/package-lock.json).
# Incremental: each source is recompiled only when it (or a header) is newer than its object.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
out=web/dist
obj=build-web/obj
mkdir -p "$out/vendor" "$obj" build-web/sysinc

# Emscripten's own tools are JavaScript run by node; Debian's emscripten finds its modules there.
export NODE_PATH=${NODE_PATH:-/usr/share/nodejs}
command -v em++ >/dev/null || { echo "build-web: em++ not found (apt-get install emscripten)" >&2; exit 2; }

# Only Boost's and Eigen's headers from the system, never all of /usr/include (glibc's headers
# would shadow Emscripten's own C library).
ln -sfn /usr/include/boost build-web/sysinc/boost
ln -sfn /usr/include/eigen3 build-web/sysinc/eigen3

flags=(-std=c++20 -O2 -Wall -Wextra -Wpedantic -Wshadow -Werror
       -Iinclude -Isrc -isystem build-web/sysinc -isystem build-web/sysinc/eigen3)

# The core library: every source below src/ except the io and paper clients and the threaded
# study runner (the page runs one case at a time, in a Web Worker).
mapfile -t sources < <(find src -name '*.cpp' -not -path 'src/io/*' -not -path 'src/paper/*' \
                         -not -path 'src/drivers/study.cpp' | sort)
sources+=(web/src/bindings.cpp)

newest_header=$(find include src -name '*.hpp' -printf '%T@\n' | sort -n | tail -1)
objects=()
stale=()
for s in "${sources[@]}"; do
  o="$obj/${s//\//_}.o"
  objects+=("$o")
  if [ ! -f "$o" ] || [ "$s" -nt "$o" ] || [ "$(stat -c %Y "$o")" -lt "${newest_header%.*}" ]; then
    stale+=("$s")
  fi
done
# Two compilers at a time (the machine is shared); xargs fails if any compile fails. Only the
# sources that throw or catch get exception support (-fexceptions): Emscripten 3.1.6 implements
# C++ exceptions in JavaScript, which routes calls out of such functions through JavaScript; the
# integrator (src/drivers/simulate.cpp, src/equations/) neither throws nor catches and stays free
# of that. The bindings catch every oscidrum::Error and hand it to the page as a message.
if [ ${#stale[@]} -gt 0 ]; then
  printf '%s\n' "${stale[@]}" | xargs -P 2 -I{} sh -c \
    'd=$1; shift; x=; grep -Eq "throw|catch" "$0" && x=-fexceptions
     echo "em++ $x $0" >&2; em++ "$@" $x -c "$0" -o "$d/$(echo "$0" | tr / _).o"' {} "$obj" "${flags[@]}"
fi

relink=0
[ -f "$out/oscidrum.wasm" ] || relink=1
for o in "${objects[@]}"; do [ "$o" -nt "$out/oscidrum.wasm" ] && relink=1; done
[ "$0" -nt "$out/oscidrum.wasm" ] && relink=1
if [ $relink = 1 ]; then
  echo "em++ (link) $out/oscidrum.js, $out/oscidrum.wasm" >&2
  em++ -O2 -fexceptions --bind "${objects[@]}" -o "$out/oscidrum.js" \
    -sMODULARIZE=1 -sEXPORT_NAME=createOscidrum -sALLOW_MEMORY_GROWTH=1 \
    -sENVIRONMENT=web,worker,node -sDISABLE_EXCEPTION_CATCHING=0
fi

# The page and its plotting library.
if [ ! -f web/node_modules/uplot/dist/uPlot.esm.js ] || \
   [ web/package-lock.json -nt web/node_modules/.package-lock.json ]; then
  (cd web && npm ci --no-audit --no-fund --loglevel=error)
fi
cp web/node_modules/uplot/dist/uPlot.esm.js web/node_modules/uplot/dist/uPlot.min.css "$out/vendor/"
cp web/node_modules/uplot/LICENSE "$out/vendor/uPlot.LICENSE"
cp web/src/*.html web/src/*.js web/src/*.css "$out/"
echo "build-web: $root/$out" >&2
