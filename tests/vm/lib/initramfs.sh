# The VM's initramfs: busybox, kernel modules, the programs under test with
# their shared libraries, /init and the test scripts (sourced).
# shellcheck shell=bash

# The modules every boot loads, dependencies first (see vm_module_closure).
# shellcheck disable=SC2034 # used by run-vm
VM_MODULES=(vcan can-raw configfs gpio-sim dummy_hcd libcomposite usb_f_fs)
# Stock programs the tests drive.
VM_TOOLS=(candump cansend cangen gpioset gpioget gpiomon gpiodetect gpioinfo gpiofind lsusb dfu-util)

# vm_stage_programs STAGE DIR PROGRAM...: copies the programs into STAGE/DIR
# and the shared libraries ldd names into the same paths under STAGE.
vm_stage_programs() {
  local stage=$1 dir=$2 program libs lib
  shift 2
  mkdir -p "$stage/$dir"
  for program in "$@"; do
    [ -f "$program" ] && [ -x "$program" ] || vm_die "program '$program' does not exist or is not executable"
    cp -L "$program" "$stage/$dir/"
    # Debug info is most of a RelWithDebInfo binary (the CLI: ~100 MB) and the VM unpacks
    # its initramfs into RAM.
    strip --strip-debug "$stage/$dir/$(basename "$program")" 2>/dev/null || :
  done
  libs=$(ldd "$@" 2>&1) || true
  if grep -q 'not found' <<<"$libs"; then
    vm_die "programs need libraries this machine lacks: $(grep -e 'not found' -e '^/' <<<"$libs" | tr -s ' \t\n' ' ')"
  fi
  for lib in $(awk '/=> \// { print $3 } /^[[:space:]]+\/[^ ]+ \(/ { print $1 }' <<<"$libs" | sort -u); do
    mkdir -p "$stage$(dirname "$lib")"
    cp -L "$lib" "$stage$lib"
  done
}

# vm_module_path MODDIR NAME: the file of module NAME (dashes and underscores
# alike), from modules.order or extra/; empty when the kernel has it built in.
vm_module_path() {
  local moddir=$1 want=${2//-/_} pattern=${2//[-_]/[-_]} rel file base
  rel=$(grep -m1 -E "(^|/)$pattern\.ko$" "$moddir/modules.order" || true)
  if [ -n "$rel" ]; then
    for file in "$moddir/$rel" "$moddir/$rel.xz" "$moddir/$rel.zst"; do
      if [ -e "$file" ]; then
        echo "$file"
        return 0
      fi
    done
    vm_die "modules.order names $rel but $moddir has no such file"
  fi
  for file in "$moddir"/extra/*.ko*; do
    base=${file##*/}
    base=${base%%.ko*}
    if [ "${base//-/_}" = "$want" ]; then
      echo "$file"
      return 0
    fi
  done
  grep -q -E "(^|/)$pattern\.ko$" "$moddir/modules.builtin" ||
    vm_die "kernel module '$2' exists neither as a module nor built in ($moddir)"
}

# vm_module_closure MODDIR NAME...: the module files NAME... need, dependencies
# first, each once. (Walking modinfo's "depends" avoids running depmod over the
# kernel's four thousand compressed modules.)
vm_module_closure() {
  local moddir=$1 name path dep
  shift
  for name in "$@"; do
    path=$(vm_module_path "$moddir" "$name")
    [ -n "$path" ] || continue
    [[ " ${VM_CLOSURE_SEEN:-} " == *" $path "* ]] && continue
    VM_CLOSURE_SEEN="${VM_CLOSURE_SEEN:-} $path"
    for dep in $(modinfo -F depends "$path" | tr ',' ' '); do
      vm_module_closure "$moddir" "$dep"
    done
    for dep in $(modinfo -F softdep "$path" | tr ' ' '\n' | grep -v ':$' || true); do
      vm_module_closure "$moddir" "$dep"
    done
    printf '%s\n' "$path"
  done
}

# vm_stage_modules STAGE KERNEL_ROOT RELEASE MODULE...: the modules and what
# they depend on, decompressed (busybox modprobe reads plain .ko), indexed by depmod.
vm_stage_modules() {
  local stage=$1 kroot=$2 release=$3 path rel target closure
  shift 3
  local src=$kroot/lib/modules/$release dst=$stage/lib/modules/$release
  VM_CLOSURE_SEEN=
  closure=$(vm_module_closure "$src" "$@")
  mkdir -p "$dst"
  for path in $closure; do
    rel=${path#"$src"/}
    target=$dst/${rel%.xz}
    target=${target%.zst}
    mkdir -p "$(dirname "$target")"
    case "$path" in
      *.ko.xz) xz -dc "$path" >"$target" ;;
      *.ko.zst) zstd -qdc "$path" >"$target" ;;
      *) cp "$path" "$target" ;;
    esac
  done
  cp "$src"/modules.order "$src"/modules.builtin "$src"/modules.builtin.modinfo "$dst/"
  depmod -b "$stage" "$release"
}

# vm_stage_base STAGE KERNEL_DIR RELEASE HERE MODULE...: everything every boot needs.
vm_stage_base() {
  local stage=$1 kdir=$2 release=$3 here=$4 busybox tool path tools=()
  shift 4
  busybox=$(command -v busybox) || vm_unavailable "busybox is not installed (Debian package busybox-static)"
  if ldd "$busybox" >/dev/null 2>&1; then
    vm_unavailable "$busybox is linked dynamically; the VM needs busybox-static"
  fi
  mkdir -p "$stage"/{bin,sbin,usr/bin,usr/sbin,usr/local/bin,etc/tetrapulse,lib/tetrapulse,proc,sys,dev,tmp,run,tests}
  cp "$busybox" "$stage/bin/busybox"
  # /init's interpreter; /init links the other applets (one process, not 300 ln).
  ln -s busybox "$stage/bin/sh"
  for tool in "${VM_TOOLS[@]}"; do
    path=$(command -v "$tool") || vm_die "'$tool' is not installed (scripts/packages.txt lists its package)"
    tools+=("$path")
  done
  vm_stage_programs "$stage" usr/bin "${tools[@]}"
  vm_stage_modules "$stage" "$kdir/root" "$release" "$@"
  printf '%s\n' "$@" >"$stage/etc/tetrapulse/modules"
  cp "$here/guest/init" "$stage/init"
  cp "$here/guest/vm-lib.sh" "$stage/lib/tetrapulse/vm-lib.sh"
  chmod 0755 "$stage/init"
}

# vm_base_initramfs CACHE KERNEL_DIR RELEASE HERE MODULE...: prints the path of
# the packed base initramfs (vm_stage_base), built once for each kernel, module
# list, set of tool binaries and version of the guest files.
vm_base_initramfs() {
  local cache=$1 kdir=$2 release=$3 here=$4 key tool out tmp
  shift 4
  key=$({
    echo "$release $(cat "$kdir/version") $*"
    cat "$here/guest/init" "$here/guest/vm-lib.sh" "$here/lib/initramfs.sh"
    for tool in busybox "${VM_TOOLS[@]}"; do
      stat -L -c '%n %s %Y' "$(command -v "$tool")" 2>/dev/null || echo "missing $tool"
    done
  } | sha256sum | cut -c1-16)
  out=$cache/initramfs/base-$key.cpio.gz
  if [ ! -f "$out" ]; then
    mkdir -p "$cache/initramfs"
    tmp=$(mktemp -d "$cache/initramfs/stage.XXXXXX")
    vm_stage_base "$tmp/root" "$kdir" "$release" "$here" "$@"
    vm_pack "$tmp/root" "$tmp/base.cpio.gz"
    mv -f "$tmp/base.cpio.gz" "$out"
    rm -rf "$tmp"
    # Only the packed files at the top: another test's boot may be staging
    # (and deleting) its own stage.* folder underneath at the same moment.
    find "$cache/initramfs" -maxdepth 1 -name 'base-*.cpio.gz' -mtime +7 -delete
  fi
  touch "$out"
  echo "$out"
}

# vm_pack STAGE OUT: a gzip'd newc cpio of STAGE, owned by root.
vm_pack() {
  (cd "$1" && find . -mindepth 1 -print0 | cpio --null -o -H newc -R 0:0 --quiet) | gzip -1 >"$2"
}
