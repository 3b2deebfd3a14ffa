# Finding and fetching Debian's kernel packages without touching the system (sourced).
# shellcheck shell=bash

# The apt mirror the machine's sources name for bookworm; the backports suite
# is taken from the same place.
vm_bookworm_mirror() {
  # shellcheck disable=SC2016 # apt's own $(FIELD) syntax, not the shell's
  apt-get indextargets --format '$(REPO_URI) $(RELEASE)' 2>/dev/null |
    awk '$2 == "bookworm" { print $1; exit }'
}

# vm_apt_options SERIES CACHE: fills the array APT_OPTS for apt-get/apt-cache.
# 6.1 is bookworm's own kernel: the system's apt configuration as it is.
# 6.12 comes from bookworm-backports: a private configuration (sources, lists,
# package cache and status inside CACHE) that never changes the system's.
vm_apt_options() {
  local series=$1 cache=$2
  APT_OPTS=(-q)
  if [ "$(id -u)" -eq 0 ]; then
    # Downloads into the cache, which the _apt sandbox user cannot write.
    APT_OPTS+=(-o APT::Sandbox::User=root)
  fi
  case "$series" in
    6.1) return 0 ;;
    6.12) ;;
    *) vm_die "unknown kernel series '$series' (known: 6.1, 6.12)" ;;
  esac
  local mirror apt=$cache/apt-backports signed=
  mirror=$(vm_bookworm_mirror)
  [ -n "$mirror" ] || vm_unavailable "no apt source of this machine names the 'bookworm' suite, so there is no mirror to take bookworm-backports from"
  mkdir -p "$apt/lists/partial" "$apt/archives/partial" "$apt/sources.list.d" "$apt/preferences.d"
  [ -f /usr/share/keyrings/debian-archive-keyring.gpg ] && signed=' [signed-by=/usr/share/keyrings/debian-archive-keyring.gpg]'
  printf 'deb%s %s bookworm-backports main\n' "$signed" "$mirror" >"$apt/sources.list"
  : >"$apt/status"
  APT_OPTS+=(
    -o "Dir::Etc::sourcelist=$apt/sources.list"
    -o "Dir::Etc::sourceparts=$apt/sources.list.d"
    -o "Dir::Etc::preferences=$apt/preferences"
    -o "Dir::Etc::preferencesparts=$apt/preferences.d"
    -o "Dir::State::lists=$apt/lists"
    -o "Dir::State::status=$apt/status"
    -o "Dir::Cache=$apt"
    -o "Dir::Cache::archives=$apt/archives"
  )
}

# vm_apt_update SERIES: refreshes the private package lists (backports only).
vm_apt_update() {
  [ "$1" = 6.1 ] && return 0
  local out
  # apt-get update only warns about an index it cannot fetch; make that an error.
  if ! out=$(apt-get "${APT_OPTS[@]}" -o APT::Update::Error-Mode=any update 2>&1) ||
    grep -q -E '^(E|W): (Failed to fetch|Some index files failed)' <<<"$out"; then
    vm_unavailable "cannot read bookworm-backports from the Debian archive ($(vm_bookworm_mirror)): $(printf '%s' "$out" | grep -E '^(E|W):' | head -3 | tr '\n' ' ')"
  fi
}

# vm_apt_depends PKG: the packages PKG depends on directly (no alternatives, no virtual ones).
vm_apt_depends() {
  apt-cache "${APT_OPTS[@]}" depends --no-recommends --no-suggests --no-conflicts \
    --no-breaks --no-replaces --no-enhances "$1" 2>/dev/null |
    awk '/^  Depends: [^<]/ { print $2 }'
}

# vm_apt_version PKG: the version apt would fetch.
vm_apt_version() {
  apt-cache "${APT_OPTS[@]}" show --no-all-versions "$1" 2>/dev/null | sed -n 's/^Version: //p' | head -1
}

# vm_apt_download DIR PKG...: fetches the .deb files into DIR.
vm_apt_download() {
  local dir=$1 out
  shift
  mkdir -p "$dir"
  if ! out=$(cd "$dir" && apt-get "${APT_OPTS[@]}" download "$@" 2>&1); then
    vm_unavailable "cannot download $* from the Debian archive: $(printf '%s' "$out" | grep -E '^(E|W):' | head -3 | tr '\n' ' ')"
  fi
}
