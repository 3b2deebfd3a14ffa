# gpio-sim and irq_sim as out-of-tree modules (sourced). Debian builds neither
# (GPIO_SIM is off, IRQ_SIM is only selected by drivers it leaves out).
# shellcheck shell=bash

# vm_gpio_sim_build SERIES RELEASE HEADERS_ROOT SOURCE_DEB OUT_DIR BUILD_DIR:
# compiles gpio-sim.ko and irq_sim.ko from SOURCE_DEB (linux-source-SERIES)
# against the headers unpacked in HEADERS_ROOT and puts them in OUT_DIR.
vm_gpio_sim_build() {
  local series=$1 release=$2 hroot=$3 source_deb=$4 out=$5 build=$6
  local kdir=$hroot/usr/src/linux-headers-$release top=linux-source-$series
  [ -f "$kdir/Makefile" ] || vm_die "headers for $release have no $kdir/Makefile"
  # Debian's per-flavour Makefile includes the common one by absolute path; point it at our copy.
  sed -i "s#^include /usr/src/#include $hroot/usr/src/#" "$kdir/Makefile"

  mkdir -p "$build" "$out"
  # Only these files are needed (6.1's gpio-sim.c also includes the private
  # gpiolib.h); tar stops reading the 150 MB archive once all are out.
  local t0=$SECONDS
  { dpkg-deb --fsys-tarfile "$source_deb" |
    tar -xO "./usr/src/$top.tar.xz" |
    xz -T0 -dc |
    tar -x --occurrence=1 --strip-components=3 -C "$build" \
      "$top/drivers/gpio/gpio-sim.c" "$top/drivers/gpio/gpiolib.h" "$top/kernel/irq/irq_sim.c"; } 2>/dev/null || true
  vm_log "sources out of $(basename "$source_deb"): $((SECONDS - t0)) s"
  if [ ! -f "$build/gpio-sim.c" ] || [ ! -f "$build/irq_sim.c" ]; then
    vm_die "$(basename "$source_deb") has no drivers/gpio/gpio-sim.c or kernel/irq/irq_sim.c"
  fi

  # irq_sim.c hands its interrupts on with handle_simple_irq(irq_to_desc(n)),
  # but a module cannot call irq_to_desc (not exported); generic_handle_irq(n)
  # does the same lookup and is exported. Built-in code also has no
  # MODULE_LICENSE, which modpost requires of a module.
  sed -i 's/handle_simple_irq(irq_to_desc(\([a-z_]*\)))/generic_handle_irq(\1)/' "$build/irq_sim.c"
  if grep -q 'irq_to_desc' "$build/irq_sim.c" || ! grep -q 'generic_handle_irq' "$build/irq_sim.c"; then
    vm_die "irq_sim.c of $top no longer calls handle_simple_irq(irq_to_desc(...)); the build-time change needs a new look"
  fi
  printf '\n#include <linux/module.h>\nMODULE_LICENSE("GPL");\nMODULE_DESCRIPTION("Interrupt simulator (built out of tree for tetrapulse tests)");\n' >>"$build/irq_sim.c"
  printf 'obj-m := gpio-sim.o irq_sim.o\n' >"$build/Kbuild"

  # No BTF for these modules: it needs pahole, and nothing here uses BTF.
  if ! make -C "$kdir" M="$build" CONFIG_DEBUG_INFO_BTF_MODULES= -j"$(nproc)" modules >"$build/build.log" 2>&1; then
    tail -30 "$build/build.log" >&2
    vm_die "building gpio-sim/irq_sim against $release failed (log above)"
  fi
  local ko
  for ko in gpio-sim.ko irq_sim.ko; do
    strip --strip-debug -o "$out/$ko" "$build/$ko"
  done
}
