#!/usr/bin/env bash
# Thumbnails every model under a folder (default ../shared/assets) inside
# GNOME's thumbnail sandbox: the arguments of
# gnome-desktop-thumbnail-script.c (read-only /usr, the usr-merged links,
# every namespace unshared, a private /tmp holding only the input file and
# the output). Prints the wall time (bwrap's start included), the exit code
# and the model. Needs bwrap (Debian's bubblewrap) and a release build:
#   cargo build --release -p zline && scripts/bwrap-thumbnails.sh [FOLDER]
set -uo pipefail
cd "$(dirname "$0")/.."
zline=$PWD/target/release/zline
folder=${1:-../shared/assets}
find "$folder" -type f \( -name '*.obj' -o -name '*.glb' -o -name '*.gltf' -o -name '*.stl' -o -name '*.ply' -o -name '*.3mf' \) \
  | grep -v -e /glTF-Draco/ -e /glTF-Embedded/ -e /glTF-Quantized/ -e glTF-Meshopt -e glTF-KTX | sort |
while read -r model; do
  ext=${model##*.}
  tmp=$(mktemp -d)
  links=()
  for d in bin lib64 lib sbin; do
    if [ -L "/$d" ]; then links+=(--symlink "/usr/$d" "/$d"); elif [ -e "/$d" ]; then links+=(--ro-bind "/$d" "/$d"); fi
  done
  start=$(date +%s%N)
  bwrap --ro-bind /usr /usr --ro-bind-try /etc/ld.so.cache /etc/ld.so.cache "${links[@]}" \
    --proc /proc --dev /dev --chdir / --setenv GIO_USE_VFS local --unshare-all --die-with-parent \
    --unsetenv DISPLAY --unsetenv WAYLAND_DISPLAY --bind "$tmp" /tmp \
    --ro-bind "$(realpath "$model")" "/tmp/gnome-desktop-file-to-thumbnail.$ext" --ro-bind "$zline" /app/zline \
    /app/zline thumbnail -s 256 "/tmp/gnome-desktop-file-to-thumbnail.$ext" /tmp/gnome-desktop-thumbnailer.png \
    2> "$tmp.err"
  code=$?
  end=$(date +%s%N)
  printf '%7.1f ms  exit %d  %s\n' "$(echo "($end - $start) / 1000000" | bc -l)" "$code" "$model"
  [ "$code" -ne 0 ] && sed 's/^/          /' "$tmp.err"
  rm -rf "$tmp" "$tmp.err"
done
