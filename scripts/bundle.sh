#!/usr/bin/env bash
# A voxgi that runs where the Debian packages are not installed (a GPU server with only its
# driver, a container): the binary, every shared library it loads (ldd) with glibc's own loader,
# libglvnd's GL and EGL dispatch libraries, the shaders and NanoVDB's GLSL header, and a `voxgi`
# launcher that starts the binary through the carried loader. The GPU driver itself (NVIDIA's
# libEGL_nvidia and its vendor file, or Mesa's) comes from the machine it runs on.
#
#   scripts/bundle.sh [--binary build/tools/voxgi] --dir OUT/          a folder
#   scripts/bundle.sh [--binary build/tools/voxgi] -o voxgi.tar.xz     the same folder, packed
#
# On the other machine: OUT/voxgi render ... (docs/gpu.md). VOXGI_BUNDLE_ONLY=1 leaves the
# machine's libraries out of the search path (what the bundle's test checks).
set -euo pipefail
cd "$(dirname "$0")/.."
binary=build/tools/voxgi
dir=""
archive=""
while [ $# -gt 0 ]; do
  case "$1" in
    --binary) binary="$2"; shift 2 ;;
    --dir) dir="$2"; shift 2 ;;
    -o) archive="$2"; shift 2 ;;
    *) echo "bundle.sh: unknown argument $1 (--binary PATH, --dir OUT or -o OUT.tar.xz)" >&2; exit 2 ;;
  esac
done
if [ -z "$dir" ] && [ -z "$archive" ]; then echo "bundle.sh: name --dir OUT or -o OUT.tar.xz" >&2; exit 2; fi
[ -x "$binary" ] || { echo "bundle.sh: $binary: not an executable (build first: scripts/build.sh)" >&2; exit 2; }
nanovdb=$(find /usr/include -path '*/nanovdb/PNanoVDB.h' -print -quit)
[ -n "$nanovdb" ] || { echo "bundle.sh: nanovdb/PNanoVDB.h not found under /usr/include" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
out="$work/voxgi"
mkdir -p "$out/bin" "$out/lib" "$out/include/nanovdb"
cp "$binary" "$out/bin/voxgi"
ldd "$binary" | awk '/=> \//{print $3} /^\s*\/lib.*ld-linux/{print $1}' | while read -r lib; do cp -L "$lib" "$out/lib/"; done
# Loaded at run time, not linked: the GL/EGL dispatch (libepoxy opens them by name).
for name in libEGL.so.1 libGL.so.1 libGLX.so.0 libOpenGL.so.0 libGLdispatch.so.0 ld-linux-x86-64.so.2; do
  # awk reads to the end: an early exit would end ldconfig with SIGPIPE, which pipefail and
  # set -e turn into the script's exit status (141) where ldconfig's list outgrows a pipe's buffer.
  path=$(ldconfig -p | awk -v n="$name" '$1 == n && /x86-64/ && p == "" {p = $NF} END {print p}')
  [ -n "$path" ] && cp -L "$path" "$out/lib/"
done
[ -f "$out/lib/ld-linux-x86-64.so.2" ] || { echo "bundle.sh: glibc's loader ld-linux-x86-64.so.2 not found" >&2; exit 2; }
cp -r shaders "$out/shaders"
cp "$nanovdb" "$out/include/nanovdb/"
cat > "$out/voxgi" <<'LAUNCHER'
#!/bin/sh
# voxgi from this folder (scripts/bundle.sh): its own libraries first, then the machine's GPU
# driver (the usual library folders, and /usr/local/nvidia where containers mount it).
here=$(dirname "$(readlink -f "$0")")
export VOXGI_SHADER_DIR="$here/shaders"
export VOXGI_SYSTEM_SHADER_INCLUDE="$here/include"
path="$here/lib"
if [ "${VOXGI_BUNDLE_ONLY:-}" != "1" ]; then
  path="$path:/usr/local/nvidia/lib64:/usr/local/nvidia/lib:/usr/lib/x86_64-linux-gnu:/lib/x86_64-linux-gnu:/usr/lib64${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
  if [ -z "${__EGL_VENDOR_LIBRARY_FILENAMES:-}" ] && [ -z "${__EGL_VENDOR_LIBRARY_DIRS:-}" ]; then
    export __EGL_VENDOR_LIBRARY_DIRS="/etc/glvnd/egl_vendor.d:/usr/share/glvnd/egl_vendor.d:/usr/local/nvidia/share/glvnd/egl_vendor.d"
  fi
fi
exec "$here/lib/ld-linux-x86-64.so.2" --library-path "$path" "$here/bin/voxgi" "$@"
LAUNCHER
chmod +x "$out/voxgi"
if [ -n "$dir" ]; then
  rm -rf "$dir"
  mkdir -p "$(dirname "$dir")"
  mv "$out" "$dir"
  echo "bundle.sh: wrote $dir ($(du -sh "$dir" | cut -f1))"
fi
if [ -n "$archive" ]; then
  src="${dir:-$out}"
  tmp="$archive.partial"
  tar -C "$(dirname "$src")" -cJf "$tmp" --transform "s|^$(basename "$src")|voxgi|" "$(basename "$src")"
  mv "$tmp" "$archive"
  echo "bundle.sh: wrote $archive ($(du -sh "$archive" | cut -f1))"
fi
