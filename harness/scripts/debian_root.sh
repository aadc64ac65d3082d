# Sourced (not run) by the scripts that work in a minimal Debian root made with debootstrap: the
# bundle's build for Debian 12's glibc (make_bundle.sh --bookworm-root), the bundle's minimal-root
# test (tests/bundle/minbase_test.sh) and the Debian 13 check (tests/debian13/debian13_test.sh).
# Every function takes the root's folder first. Needs root (debootstrap, chroot, mounts) and
# Debian's mirror ($SDFBENCH_DEBIAN_MIRROR, default deb.debian.org).

debian_root_mirror=${SDFBENCH_DEBIAN_MIRROR:-http://deb.debian.org/debian}

# Unmounts everything mounted inside the root (also by an earlier run that was killed), deepest
# first, so that rm never walks into the host's /dev.
debian_root_unmount() {
  local m
  for m in $(awk -v r="$1/" 'index($2, r) == 1 {print $2}' /proc/mounts | sort -r); do umount -l "$m" || true; done
}

debian_root_remove() {
  debian_root_unmount "$1"
  rm -rf --one-file-system "$1"
}

# debian_root_make ROOT CODENAME LOG: a `debootstrap --variant=minbase CODENAME` root at ROOT, or
# the one already there from an earlier call (its marker file names the release). Returns 1, with
# the log's tail on stderr, when debootstrap fails.
debian_root_make() {
  local root=$1 codename=$2 log=$3
  [[ $(cat "$root/.sdfbench-root-ready" 2>/dev/null) == "$codename" ]] && return 0
  command -v debootstrap >/dev/null || apt-get install -y -qq --no-install-recommends debootstrap >/dev/null ||
    { apt-get update -qq && apt-get install -y -qq --no-install-recommends debootstrap >/dev/null; }
  debian_root_remove "$root"
  mkdir -p "$root" "$(dirname "$log")"
  if ! debootstrap --variant=minbase "$codename" "$root" "$debian_root_mirror" >"$log" 2>&1; then
    tail -20 "$log" >&2
    return 1
  fi
  echo "$codename" >"$root/.sdfbench-root-ready"
}

# Mounts /proc, /sys and the host's /dev in the root and gives it the host's resolver.
debian_root_mount() {
  debian_root_unmount "$1"
  mount -t proc proc "$1/proc"
  mount -t sysfs sys "$1/sys"
  mount --bind /dev "$1/dev"
  cp /etc/resolv.conf "$1/etc/resolv.conf"
}

# debian_root_run ROOT COMMAND...: COMMAND inside the root with a clean environment.
debian_root_run() {
  local root=$1
  shift
  chroot "$root" /usr/bin/env -i PATH=/usr/sbin:/usr/bin:/sbin:/bin HOME=/root "$@"
}

# debian_root_copy_checkout ROOT DEST: this checkout (the current folder: tracked and untracked
# files that git does not ignore, and the git folder, so that builds are stamped with the commit)
# into ROOT/DEST. What was there is replaced, except build/, out/ and .deps/ of an earlier run.
debian_root_copy_checkout() {
  local dest=$1$2
  mkdir -p "$dest"
  find "$dest" -mindepth 1 -maxdepth 1 ! -name build ! -name .deps ! -name out -exec rm -rf {} +
  { git ls-files -co --exclude-standard -z; find .git -print0; } | tar --null --no-recursion -T - -cf - | tar -C "$dest" -xf -
}
