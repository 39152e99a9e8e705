#!/usr/bin/env bash
# The wheel in a clean room (docs/python.md, "The wheel"): a minimal Debian 12
# root made by `debootstrap --variant=minbase` from Debian's archive (the
# mirror this machine's apt uses) with Python, its venv and Mesa's EGL and GL
# drivers, and nothing else: no compiler, no -dev package, no ffmpeg, no X
# server. In it, a venv gets the wheel and the pinned pyvista and vtk from
# PyPI, and python/package_tests/clean_room.py draws an animated,
# flow-aligned texture off-screen with add_flow and writes a video with the
# console script.
#
#   scripts/clean-room.sh WHEEL...     (as root; each wheel tested in turn)
#
# The root is made once and kept, keyed by its package list, under
# IBFVS_CLEAN_ROOT_CACHE (default /var/cache/ibfvs); each run works in a
# copy, so nothing a test installs stays. pip's downloads are cached there
# too.
set -euo pipefail
root_dir="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cache="${IBFVS_CLEAN_ROOT_CACHE:-/var/cache/ibfvs}"
# Python and its venv; libegl1 (GLVND's EGL, which depends on Mesa's
# libegl-mesa0), libgl1-mesa-dri (llvmpipe) and libopengl0 (GLVND's
# libOpenGL.so.0: libepoxy takes OpenGL 1.x's functions from it or from
# libGL.so.1, which every desktop has; without either the wheel says so
# and what to install). Nothing else is named.
packages=python3,python3-venv,libegl1,libgl1-mesa-dri,libopengl0
key="$(printf 'bookworm minbase %s' "$packages" | sha256sum | cut -c1-12)"
base="$cache/clean-root-$key.tar"
(($(id -u) == 0)) || { echo "clean-room: needs root (debootstrap, chroot)" >&2; exit 1; }
(($#)) || { echo "usage: scripts/clean-room.sh WHEEL..." >&2; exit 2; }

mirror() {
  # The archive this machine's apt reads (deb822 or one-line sources).
  local m
  m="$(grep -hs '^URIs:' /etc/apt/sources.list.d/*.sources | awk '{print $2}' | grep -v security | head -n1)"
  [[ -n $m ]] || m="$(grep -hs '^deb ' /etc/apt/sources.list | awk '{print $2}' | grep -v security | head -n1)"
  [[ -n $m ]] || { echo "clean-room: no Debian mirror in /etc/apt" >&2; return 1; }
  echo "$m"
}
make_base() {
  [[ -f $base ]] && return 0
  local tmp
  tmp="$(mktemp -d "$cache/root.XXXXXX")"
  echo "clean-room: debootstrap --variant=minbase bookworm with $packages"
  debootstrap --variant=minbase --include="$packages" bookworm "$tmp/root" "$(mirror)" >"$tmp/debootstrap.log" 2>&1 ||
    { tail -n 20 "$tmp/debootstrap.log" >&2; rm -rf "$tmp"; return 1; }
  rm -rf "$tmp/root/var/cache/apt/archives/"*.deb
  tar -C "$tmp/root" -cf "$tmp/root.tar" .
  mv "$tmp/root.tar" "$base"
  rm -rf "$tmp"
}
mkdir -p "$cache/pip"
make_base
[[ ${1:-} == --make-root ]] && exit 0

room=""
leave_room() {
  # Whatever happens (an error, Ctrl-C, a kill): nothing stays mounted, and
  # the copy goes without crossing into what was mounted in it.
  [[ -n $room && -d $room ]] || return 0
  local m
  for m in "$room"/root/.cache/pip "$room"/proc "$room"/dev; do
    if mountpoint -q "$m"; then umount -l "$m"; fi
  done
  rm -rf --one-file-system "$room"
  room=""
}
trap leave_room EXIT
trap 'exit 130' INT TERM

run_in_room() {
  local wheel=$1
  room="$(mktemp -d "$cache/room.XXXXXX")"
  tar -C "$room" -xf "$base"
  mount --bind /dev "$room/dev"
  mount -t proc proc "$room/proc"
  mkdir -p "$room/root/.cache/pip" "$room/tests"
  mount --bind "$cache/pip" "$room/root/.cache/pip"
  cp /etc/resolv.conf "$room/etc/resolv.conf"  # pip reaches PyPI
  # pip in the room trusts what this machine's pip trusts (a site's own
  # certificate authority for its way out, where it has one).
  local cert="${PIP_CERT:-$(python3 -m pip config get global.cert 2>/dev/null || true)}" pip_cert=()
  if [[ -n $cert && -f $cert ]]; then
    cp "$cert" "$room/etc/pip-ca.crt"
    pip_cert=(PIP_CERT=/etc/pip-ca.crt)
  fi
  cp "$wheel" "$room/tests/"
  cp "$root_dir"/python/package_tests/{conftest.py,test_pyvista.py,test_wheel.py} "$room/tests/"
  local in_room=(chroot "$room" /usr/bin/env -i HOME=/root PATH=/opt/venv/bin:/usr/bin:/bin LANG=C.UTF-8
    "${pip_cert[@]}")
  echo "clean-room: the root has no compiler, no X server, no ffmpeg:"
  for program in cc gcc Xvfb ffmpeg; do
    if "${in_room[@]}" sh -c "command -v $program" >/dev/null; then
      echo "clean-room: $program is in the root" >&2
      return 1
    fi
  done
  "${in_room[@]}" python3 -m venv /opt/venv
  # The wheel with its pyvista extra (pyvista, vtk, imageio, imageio-ffmpeg), and pytest.
  "${in_room[@]}" pip install -q "/tests/$(basename "$wheel")[pyvista]" pytest==9.2.0
  # add_flow draws the swirl along the flow and animates it off-screen (VTK's
  # EGL window on llvmpipe); the console script writes a video; the wheel's
  # libraries are all found there.
  "${in_room[@]}" IBFVS_WHEEL="/tests/$(basename "$wheel")" sh -c 'cd /tests && python -m pytest -q -p no:cacheprovider \
    test_pyvista.py::test_the_swirl_is_drawn_along_the_flow_and_animates \
    test_wheel.py::test_the_console_script_writes_a_video \
    test_wheel.py::test_the_module_and_the_command_find_every_library'
  # Without OpenGL's library (libOpenGL.so.0 moved aside in this copy): one
  # error that says what to install, from the command and from Python, not
  # libepoxy's abort.
  local gl
  gl="$(ls "$room"/usr/lib/x86_64-linux-gnu/libOpenGL.so.0*)"
  mkdir "$room/aside" && mv $gl "$room/aside/"
  local said status=0
  said="$("${in_room[@]}" ibfvs render --mesh torus --frames 1 --size 8x8 --out /tmp/x.png 2>&1)" || status=$?
  echo "clean-room: without libOpenGL.so.0 the command says: $said"
  [[ $status == 1 && $(wc -l <<<"$said") == 1 && $said == *libopengl0* ]] ||
    { echo "clean-room: expected one error line naming libopengl0 (exit $status)" >&2; return 1; }
  "${in_room[@]}" python -c '
import ibfvs
try:
    ibfvs.render("torus", size=(8, 8), frames=1)
except RuntimeError as e:
    assert "libopengl0" in str(e), e
    print("clean-room: and Python raises RuntimeError:", e)
else:
    raise SystemExit("no error without libOpenGL.so.0")'
  mv "$room"/aside/* "$room/usr/lib/x86_64-linux-gnu/"
}
for wheel in "$@"; do
  echo "clean-room: $(basename "$wheel")"
  run_in_room "$(realpath "$wheel")"
  leave_room
done
