# A Debian kernel with its modules and an out-of-tree gpio-sim, cached per series (sourced).
# shellcheck shell=bash
# Needs common.sh, debian_archive.sh and gpio_sim.sh.

# vm_kernel_packages SERIES: resolves the current kernel of SERIES and sets
# KERNEL_RELEASE (uname -r), KERNEL_VERSION (Debian version) and KERNEL_DEBS
# (image, headers, their common headers and kbuild, and linux-source).
vm_kernel_packages() {
  local series=$1 image headers common kbuild
  image=$(vm_apt_depends linux-image-amd64 | grep -E "^linux-image-${series//./\\.}\.[^ ]*-amd64$" | head -1 || true)
  [ -n "$image" ] || vm_unavailable "apt knows no linux-image-${series}.*-amd64 behind linux-image-amd64 (for 6.1 the system's apt lists may need an 'apt-get update')"
  KERNEL_RELEASE=${image#linux-image-}
  KERNEL_VERSION=$(vm_apt_version "$image")
  headers=linux-headers-$KERNEL_RELEASE
  common=$(vm_apt_depends "$headers" | grep -E '^linux-headers-.*-common$' | head -1 || true)
  kbuild=$(vm_apt_depends "$headers" | grep -E '^linux-kbuild-' | head -1 || true)
  [ -n "$common" ] && [ -n "$kbuild" ] || vm_unavailable "apt cannot resolve the headers of $image ($headers: common '$common', kbuild '$kbuild')"
  # linux-source must be the same upload as the image, or the module would be
  # built from other sources than the kernel it loads into.
  KERNEL_DEBS=("$image" "$headers" "$common" "$kbuild" "linux-source-$series=$KERNEL_VERSION")
}

# vm_unpack_debs DIR DEB...: unpacks the packages' files into DIR (no scripts run).
vm_unpack_debs() {
  local dir=$1 deb
  shift
  for deb in "$@"; do dpkg-deb -x "$deb" "$dir"; done
}

# vm_kernel_build SERIES DIR: fetches and unpacks the kernel into DIR, builds gpio-sim.
vm_kernel_build() {
  local series=$1 dir=$2 work=$2.partial
  rm -rf "$work"
  mkdir -p "$work"
  vm_log "fetching kernel $KERNEL_RELEASE ($KERNEL_VERSION) and its headers and sources"
  vm_timed "download" vm_apt_download "$work/debs" "${KERNEL_DEBS[@]}"
  vm_timed "unpack image" dpkg-deb -x "$work"/debs/linux-image-*.deb "$work/root"
  vm_timed "unpack headers" vm_unpack_debs "$work/headers" "$work"/debs/linux-headers-*.deb "$work"/debs/linux-kbuild-*.deb
  [ -f "$work/root/boot/vmlinuz-$KERNEL_RELEASE" ] || vm_die "linux-image package has no boot/vmlinuz-$KERNEL_RELEASE"
  mv "$work/root/boot/vmlinuz-$KERNEL_RELEASE" "$work/vmlinuz"
  mv "$work/root/boot/config-$KERNEL_RELEASE" "$work/config"
  rm -rf "$work/root/boot" "$work/root/usr"

  vm_timed "gpio-sim build" vm_gpio_sim_build "$series" "$KERNEL_RELEASE" "$work/headers" "$work"/debs/linux-source-*.deb \
    "$work/root/lib/modules/$KERNEL_RELEASE/extra" "$work/gpio-sim-build"

  # The headers stay (unused from here on): deleting their 17,000 files took
  # 40 s on the ext4 (mounted with discard) of the build machines.
  rm -rf "$work/debs" "$work/gpio-sim-build"
  printf '%s\n' "$KERNEL_RELEASE" >"$work/release"
  printf '%s\n' "$KERNEL_VERSION" >"$work/version"
  rm -rf "$dir"
  mv "$work" "$dir"
}

# vm_kernel_prepare SERIES CACHE: makes sure CACHE/kernel-SERIES holds a ready
# kernel; sets KERNEL_DIR and KERNEL_RELEASE. A cached kernel is used as it is
# (offline, reproducible) unless TETRAPULSE_VM_REFRESH=1 asks for the current one.
vm_kernel_prepare() {
  local series=$1 cache=$2
  KERNEL_DIR=$cache/kernel-$series
  if [ -f "$KERNEL_DIR/release" ] && [ "${TETRAPULSE_VM_REFRESH:-0}" != 1 ]; then
    KERNEL_RELEASE=$(cat "$KERNEL_DIR/release")
    return 0
  fi
  vm_apt_options "$series" "$cache"
  vm_timed "package lists" vm_apt_update "$series"
  vm_timed "resolve packages" vm_kernel_packages "$series"
  if [ -f "$KERNEL_DIR/release" ] && [ "$(cat "$KERNEL_DIR/release")" = "$KERNEL_RELEASE" ] &&
    [ "$(cat "$KERNEL_DIR/version")" = "$KERNEL_VERSION" ]; then
    return 0
  fi
  local started=$SECONDS
  vm_kernel_build "$series" "$KERNEL_DIR"
  vm_log "kernel $KERNEL_RELEASE ready in $((SECONDS - started)) s ($KERNEL_DIR)"
}
