#!/usr/bin/env bash
# Packaging test: builds the h4cam .deb with CPack into a scratch directory, installs it into
# a scratch root with dpkg --root (unpack only: no maintainer script runs there), and checks
# what a camera module would get: the control fields, the files, the conffile, the systemd
# unit (systemd-analyze verify; systemd-analyze security: exposure 2.0 or lower; and that it
# names the packaged binary, the h4cam user, the video group and the packaged
# configuration), and what postinst does, with stand-ins for adduser/systemctl so nothing on
# this machine changes.
#   check_deb.sh BUILD_DIR TARGET_ARCH VERSION [BOARDS_DIR]
# TARGET_ARCH: "native" (a native build: dpkg's architecture) or the cross target's
# processor (aarch64 -> arm64).
# Exit 77 (ctest: skipped) when dpkg-deb is missing.
set -euo pipefail

build_dir=$1
arch=$2
version=$3
boards_dir=${4:-}

if ! command -v dpkg-deb >/dev/null || ! command -v dpkg >/dev/null; then
  echo "SKIPPED: dpkg-deb/dpkg not found: the .deb cannot be built or inspected here" \
       "(Debian: apt-get install dpkg-dev)"
  exit 77
fi
case "$arch" in
  native) arch=$(dpkg --print-architecture) ;;
  aarch64 | arm64) arch=arm64 ;;
  x86_64) arch=amd64 ;;
esac

failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
pass() { echo "ok:   $*"; }
check() {  # check DESCRIPTION COMMAND...
  local what=$1; shift
  if "$@"; then pass "$what"; else fail "$what"; fi
}

scratch=$(mktemp -d "${TMPDIR:-/tmp}/h4cam-deb-test.XXXXXX")
trap 'rm -rf "$scratch"' EXIT

# --- the package ---
if ! cpack --config "$build_dir/CPackConfig.cmake" -G DEB -B "$scratch/out" > "$scratch/cpack.log" 2>&1; then
  cat "$scratch/cpack.log"
  echo "FAIL: cpack could not make the package"
  exit 1
fi
deb=$scratch/out/h4cam_${version}_${arch}.deb
if [ ! -f "$deb" ]; then
  ls -l "$scratch/out"
  echo "FAIL: expected $deb (h4cam_<version>_<arch>.deb)"
  exit 1
fi
pass "cpack made $(basename "$deb")"

field() { dpkg-deb -f "$deb" "$1"; }
check "Package is h4cam" [ "$(field Package)" = h4cam ]
check "Architecture is $arch" [ "$(field Architecture)" = "$arch" ]
check "Version is $version" [ "$(field Version)" = "$version" ]
depends=$(field Depends)
echo "      Depends: $depends"
# (libssl3: libcrypto, the HMAC of authenticated bus messages.
# dpkg-shlibdeps leaves out a library none of whose symbols h4cam uses: liblcm appears once
# the service publishes; it is not required here.)
for dependency in adduser libcamera-ipa libc6 libstdc++6 libcamera0 libopencv-core4 \
  libopencv-calib3d4 libapriltag libssl3; do
  check "Depends names $dependency" grep -q "\\b$dependency" <<< "$depends"
done

dpkg-deb -e "$deb" "$scratch/control"
check "conffiles lists /etc/h4cam/h4cam.yaml" grep -qx /etc/h4cam/h4cam.yaml "$scratch/control/conffiles"
for script in postinst prerm postrm; do
  check "$script is an executable maintainer script" [ -x "$scratch/control/$script" ]
done

# --- install into a scratch root ---
root=$scratch/root
mkdir -p "$root/var/lib/dpkg/info" "$root/var/lib/dpkg/updates" "$root/var/lib/dpkg/triggers"
touch "$root/var/lib/dpkg/status" "$root/var/lib/dpkg/available"
if dpkg --root="$root" --force-not-root --force-depends --force-architecture \
     --log=/dev/null --unpack "$deb" > "$scratch/dpkg.log" 2>&1; then
  pass "dpkg --root --unpack"
else
  cat "$scratch/dpkg.log"
  fail "dpkg --root --unpack"
fi
check "dpkg records h4cam as unpacked in the scratch root" \
  grep -qx "Status: install ok unpacked" <(dpkg --root="$root" -s h4cam 2>/dev/null)

binary=$root/usr/bin/h4cam
unit=$root/lib/systemd/system/h4cam.service
config=$root/etc/h4cam/h4cam.yaml
check "the package holds /etc/h4cam/h4cam.yaml" grep -q ' \./etc/h4cam/h4cam\.yaml$' <(dpkg-deb -c "$deb")
# Unpacked but not configured, dpkg keeps a conffile as <name>.dpkg-new (configure renames it;
# configuring would run postinst, which must not run on this machine).
[ -f "$config" ] || [ ! -f "$config.dpkg-new" ] || mv "$config.dpkg-new" "$config"
check "/usr/bin/h4cam is installed and executable" [ -x "$binary" ]
case "$arch" in
  amd64) elf_machine="x86-64" ;;
  arm64) elf_machine="ARM aarch64" ;;
  *) elf_machine="" ;;
esac
if command -v file >/dev/null && [ -n "$elf_machine" ] && [ -f "$binary" ]; then
  check "/usr/bin/h4cam is an $elf_machine ELF program" grep -q "ELF 64-bit.*$elf_machine" <(file -b "$binary")
fi
check "the unit is /lib/systemd/system/h4cam.service" [ -f "$unit" ]
check "the default configuration is /etc/h4cam/h4cam.yaml" [ -f "$config" ]
check "the README is in /usr/share/doc/h4cam" [ -f "$root/usr/share/doc/h4cam/README.md" ]
if [ -n "$boards_dir" ]; then
  for board in "$boards_dir"/*.yaml "$boards_dir"/*.svg "$boards_dir"/*.pdf; do
    [ -f "$board" ] || continue
    check "board $(basename "$board") is in /usr/share/h4cam/boards" \
      cmp -s "$board" "$root/usr/share/h4cam/boards/$(basename "$board")"
  done
fi

# --- the unit ---
unit_value() {  # the last assignment of KEY in the unit (systemd's rule for single values)
  sed -n "s/^$1=//p" "$unit" | tail -1
}
exec_start=$(unit_value ExecStart)
check "ExecStart runs /usr/bin/h4cam run --config /etc/h4cam/h4cam.yaml" \
  [ "$exec_start" = "/usr/bin/h4cam run --config /etc/h4cam/h4cam.yaml" ]
check "ExecStart's program is the packaged one" [ -x "$root${exec_start%% *}" ]
check "ExecStart's configuration is the packaged one" [ -f "$root${exec_start##* }" ]
check "runs as the user h4cam" [ "$(unit_value User)" = h4cam ]
check "in the video group" grep -qw video <<< "$(unit_value SupplementaryGroups)"
check "Type=notify (READY=1 from h4cam)" [ "$(unit_value Type)" = notify ]
check "has a watchdog" grep -qE '^[1-9][0-9]*(s|min)?$' <<< "$(unit_value WatchdogSec)"
check "restarts on failure" [ "$(unit_value Restart)" = on-failure ]
check "NoNewPrivileges=yes" [ "$(unit_value NoNewPrivileges)" = yes ]
check "ProtectSystem=strict" [ "$(unit_value ProtectSystem)" = strict ]
check "ProtectHome=yes" [ "$(unit_value ProtectHome)" = yes ]
check "no PrivateDevices (libcamera needs /dev/media*, /dev/video*)" \
  [ -z "$(unit_value PrivateDevices)" ]
check "LCM stays on the machine by default (ttl=0)" \
  grep -qx 'LCM_DEFAULT_URL=udpm://239.255.76.67:7667?ttl=0' <<< "$(unit_value Environment)"
check "logs to the journal" [ "$(unit_value StandardOutput)" = journal ]

if command -v systemd-analyze >/dev/null; then
  # --root: ExecStart= and the unit's other paths are looked up inside the scratch root. The
  # unit's implicit and explicit dependencies (sysinit.target, network-online.target, ...)
  # come from the running system's targets, copied in: a scratch root has none. Any
  # message (unknown key, bad value, missing program) fails the check, not only the status.
  for dir in /lib/systemd/system /usr/lib/systemd/system; do
    [ -d "$dir" ] && find "$dir" -maxdepth 1 -name '*.target' -exec cp -an {} "$root/lib/systemd/system/" \;
  done
  if systemd-analyze verify --root="$root" --man=no /lib/systemd/system/h4cam.service \
       > "$scratch/verify.log" 2>&1 && [ ! -s "$scratch/verify.log" ]; then
    pass "systemd-analyze verify"
  else
    cat "$scratch/verify.log"
    fail "systemd-analyze verify"
  fi
  # The exposure score of the shipped unit (0 = locked down, 10 = unprotected): 2.0 or
  # lower. --threshold takes tenths; the score is printed for the log either way.
  if systemd-analyze security --offline=true --root="$root" --threshold=20 \
       /lib/systemd/system/h4cam.service > "$scratch/security.log" 2>&1; then
    pass "systemd-analyze security: $(grep -o 'exposure level[^:]*: [0-9.]*' "$scratch/security.log")"
  else
    grep -E '✗|exposure' "$scratch/security.log" || cat "$scratch/security.log"
    fail "systemd-analyze security: exposure above 2.0"
  fi
else
  fail "systemd-analyze not found: install systemd (scripts/setup does)"
fi

# --- postinst, with stand-ins: a fresh machine without the user ---
stubs=$scratch/stubs
mkdir -p "$stubs"
for tool in adduser systemctl; do
  printf '#!/bin/sh\necho "%s $*" >> "%s/calls"\n' "$tool" "$scratch" > "$stubs/$tool"
done
printf '#!/bin/sh\nexit 2\n' > "$stubs/getent"                  # no such user yet
printf '#!/bin/sh\necho h4cam\n' > "$stubs/id"                  # not in video yet
chmod +x "$stubs"/*
if env -i PATH="$stubs:/usr/bin:/bin" sh "$scratch/control/postinst" configure "" \
     > "$scratch/postinst.log" 2>&1; then
  pass "postinst configure succeeds"
else
  cat "$scratch/postinst.log"
  fail "postinst configure"
fi
touch "$scratch/calls"
check "postinst creates the system user h4cam" \
  grep -qE '^adduser --system .*--group .* h4cam$' "$scratch/calls"
check "postinst adds h4cam to video" grep -qx 'adduser h4cam video' "$scratch/calls"

if [ $failures -gt 0 ]; then
  echo "$failures check(s) failed"
  exit 1
fi
echo "all packaging checks passed for $(basename "$deb")"
