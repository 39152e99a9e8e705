# What scripts/cfd_case.sh and scripts/cfd_transient.sh share (sourced):
# Debian's OpenFOAM installed where missing, a tutorial copied into its
# case folder, and each step run with its log. The caller sets `me` (its
# name, for messages) first.

log() { printf '%s  %s\n' "$(date +%T)" "$*"; }

# Installs openfoam and openfoam-examples unless SOLVER runs and TUTORIAL is there.
need_openfoam() {
  local solver=$1 tutorial=$2
  if ! command -v "$solver" > /dev/null || [[ ! -d $tutorial ]]; then
    local sudo=""
    [[ $(id -u) -ne 0 ]] && sudo="sudo"
    log "installing Debian's openfoam and openfoam-examples"
    $sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends \
      openfoam openfoam-examples > /dev/null
  fi
  # OpenFOAM's binaries need only this (its etc/bashrc is broken in Debian's build).
  export WM_PROJECT_DIR=/usr/share/openfoam
}

# A fresh copy of TUTORIAL in CASE_DIR, uncompressed; the shell is left in it.
copy_tutorial() {
  local tutorial=$1 case_dir=$2
  rm -rf "$case_dir"
  mkdir -p "$case_dir"
  cp -r "$tutorial"/. "$case_dir"/
  cd "$case_dir"
  find . -name '*.gz' -exec gunzip -f {} +
}

# Runs a step (its name, then the command) into log.NAME; on failure says
# where and shows the log's end.
run() {
  local step=$1
  shift
  log "$step"
  "$@" > "log.$step" 2>&1 || {
    echo "$me: $step failed; see $PWD/log.$step" >&2
    tail -n 20 "log.$step" >&2
    exit 1
  }
}

# The wall patches of the case's mesh (type wall in its boundary file), space-separated.
wall_patches() {
  awk '/^ *[A-Za-z_][A-Za-z0-9_]* *$/ { name = $1 } /type +wall;/ { print name }' \
    constant/polyMesh/boundary | tr '\n' ' ' | sed 's/ $//'
}
