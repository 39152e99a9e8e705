#!/usr/bin/env bash
# Fetches the real data ibfvs uses from Debian packages into a git-ignored
# folder: downloaded with apt-get download, extracted, never installed.
#   data/meshes/  from libcgal-demo (data.tar.gz): the paper's cow, the bunny, ...
#   data/earth/   from ferret-datasets: monthly winds, COADS climatology, relief
# Usage: scripts/fetch_data.sh [DATA_DIR]   (default: data/ in the repository)
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
data=${1:-${IBFVS_DATA_DIR:-$here/data}}
meshes=(cow.off bunny00.off elephant.off knot.off mannequin-devil.off)
earth=(monthly_navy_winds.cdf coads_climatology.cdf etopo20.cdf etopo60.cdf)

have() {  # have FOLDER FILE...: all present and non-empty
  local dir=$1
  shift
  for f in "$@"; do [[ -s $dir/$f ]] || return 1; done
}

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# apt-get download writes as the _apt user where it can.
chmod 777 "$work"

download() {  # download PACKAGE: the .deb into $work, fetching package lists if needed
  local pkg=$1
  (cd "$work" && apt-get download "$pkg" >>download.log 2>&1) && return 0
  # A fresh machine may have no package lists yet; root can fetch them.
  if [[ $(id -u) -eq 0 ]] && apt-get update -qq >>"$work/download.log" 2>&1 &&
    (cd "$work" && apt-get download "$pkg" >>download.log 2>&1); then
    return 0
  fi
  cat "$work/download.log" >&2
  echo "fetch_data: apt-get download $pkg failed (run 'apt-get update' first?)" >&2
  exit 1
}

if have "$data/meshes" "${meshes[@]}"; then
  echo "fetch_data: meshes already in $data/meshes"
else
  download libcgal-demo
  dpkg-deb -x "$work"/libcgal-demo_*.deb "$work/cgal"
  members=()
  for m in "${meshes[@]}"; do members+=("data/meshes/$m"); done
  tar xzf "$work/cgal/usr/share/doc/libcgal-dev/data.tar.gz" -C "$work" "${members[@]}"
  mkdir -p "$data/meshes"
  for m in "${meshes[@]}"; do cp "$work/data/meshes/$m" "$data/meshes/$m"; done
  echo "fetch_data: wrote ${meshes[*]} to $data/meshes"
fi

if have "$data/earth" "${earth[@]}"; then
  echo "fetch_data: earth data already in $data/earth"
else
  download ferret-datasets
  dpkg-deb -x "$work"/ferret-datasets_*.deb "$work/ferret"
  mkdir -p "$data/earth"
  for f in "${earth[@]}"; do cp "$work/ferret/usr/share/ferret-vis/data/$f" "$data/earth/$f"; done
  echo "fetch_data: wrote ${earth[*]} to $data/earth"
fi
