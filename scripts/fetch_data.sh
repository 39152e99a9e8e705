#!/usr/bin/env bash
# Fetches the real meshes ibfvs uses from Debian's libcgal-demo package into
# data/meshes (git-ignored): downloaded with apt-get, extracted, never installed.
# Usage: scripts/fetch_data.sh [DATA_DIR]   (default: data/ beside this script's repo)
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
data=${1:-${IBFVS_DATA_DIR:-$here/data}}
meshes=(cow.off bunny00.off elephant.off knot.off mannequin-devil.off)

have_all=1
for m in "${meshes[@]}"; do [[ -s $data/meshes/$m ]] || have_all=0; done
if ((have_all)); then
  echo "fetch_data: meshes already in $data/meshes"
  exit 0
fi

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
# apt-get download writes as the _apt user where it can; a private folder it
# cannot enter only costs a warning.
chmod 777 "$work"
if ! apt-get download libcgal-demo >download.log 2>&1; then
  # A fresh machine may have no package lists yet; root can fetch them.
  if [[ $(id -u) -eq 0 ]] && apt-get update -qq >>download.log 2>&1 &&
    apt-get download libcgal-demo >>download.log 2>&1; then
    :
  else
    cat download.log >&2
    echo "fetch_data: apt-get download libcgal-demo failed (run 'apt-get update' first?)" >&2
    exit 1
  fi
fi
dpkg-deb -x libcgal-demo_*.deb pkg
members=()
for m in "${meshes[@]}"; do members+=("data/meshes/$m"); done
tar xzf pkg/usr/share/doc/libcgal-dev/data.tar.gz "${members[@]}"
mkdir -p "$data/meshes"
for m in "${meshes[@]}"; do cp "data/meshes/$m" "$data/meshes/$m"; done
echo "fetch_data: wrote ${meshes[*]} to $data/meshes"
