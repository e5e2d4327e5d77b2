#!/usr/bin/env bash
# Installed like a tool: `cmake --install BUILD --prefix P` (every component, as after the
# demo) writes nothing outside P (issue 43: the camera's unit and configuration went to /etc
# and /lib/systemd whatever the prefix), the unit it puts in P names P's program and
# configuration; it puts h4cal and h4cam in bin, their man pages in share/man/man1 (one section per subcommand), the boards
# in share/h4cal/boards and the documentation in share/doc/h4cal; both installed programs
# answer --version and --help, and so does every subcommand (exit 0, non-empty output).
# Then the workstation package, h4cal_<version>_<arch>.deb (cpack --config
# CPackConfig-h4cal.cmake), holds the same files under /usr. Exit 77 (skipped) when dpkg-deb
# is missing, for the package part only.
#   install_test.sh BUILD_DIR VERSION
set -euo pipefail
build=$(realpath "$1") version=$2
scratch=$(mktemp -d "${TMPDIR:-/tmp}/h4-install-test.XXXXXX")
trap 'rm -rf "$scratch"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

DESTDIR=$scratch/root cmake --install "$build" --prefix /opt/h4 > "$scratch/install.log" 2>&1 \
  || { cat "$scratch/install.log"; fail "cmake --install"; }
prefix=$scratch/root/opt/h4
# What the install copies from the build tree (the install rules name it) is made by the
# target h4_workstation, all that scripts/demo builds: installing after the demo works.
if [ -f "$build/build.ninja" ]; then
  inputs() {  # the inputs ninja names for each target (not what it feeds: "outputs:")
    for target in "$@"; do
      ninja -C "$build" -t query "$target" |
        awk '/^  input:/ { on = 1; next } /^  outputs:/ { on = 0 } on { print $NF }'
    done
  }
  first=$(inputs h4_workstation)
  made=$(printf '%s\n' $first; inputs $first)
  copied=$(grep -rh '^ *file(INSTALL ' "$build" --include=cmake_install.cmake |
             grep -oE "\"$build/[^\"]+\"" | tr -d '"' | sort -u)
  [ -n "$copied" ] || fail "no install rule copies a file of the build tree: the check reads nothing"
  for file in $copied; do
    grep -qxF "${file#"$build"/}" <<< "$made" ||
      fail "cmake --install copies ${file#"$build"/}, which target h4_workstation (the demo's build) does not make"
  done
fi
# A scratch DESTDIR, so that a rule escaping the prefix lands in it, where it shows.
outside=$(find "$scratch/root" -not -type d -not -path "$prefix/*")
[ -z "$outside" ] || fail "cmake --install --prefix /opt/h4 wrote outside the prefix: $outside"
unit=$prefix/lib/systemd/system/h4cam.service
[ -s "$unit" ] || fail "the camera service's unit is not in P/lib/systemd/system"
[ -s "$prefix/etc/h4cam/h4cam.yaml" ] || fail "the camera's configuration is not in P/etc/h4cam"
grep -qx "ExecStart=/opt/h4/bin/h4cam run --config /opt/h4/etc/h4cam/h4cam.yaml" "$unit" ||
  fail "the unit does not run P's h4cam with P's configuration: $(grep ExecStart= "$unit")"

subcommands() {  # CLI11's listing of the program's subcommands
  "$1" --help | sed -nE '/^(Subcommands|SUBCOMMANDS):/,/^$/ s/^  ([a-z][a-z0-9-]*)( .*)?$/\1/p'
}
checked=0
for name in h4cal h4cam; do
  program=$prefix/bin/$name
  [ -x "$program" ] || fail "$program is not installed"
  out=$("$program" --version) || fail "$name --version exited $?"
  [ "$out" = "$name $version" ] || fail "$name --version printed '$out'"
  "$program" --help > "$scratch/help" || fail "$name --help exited $?"
  [ -s "$scratch/help" ] || fail "$name --help printed nothing"
  page=$prefix/share/man/man1/$name.1
  [ -s "$page" ] || fail "no man page $page"
  grep -q "$version" "$page" || fail "$page does not carry the version $version"
  for section in '"EXIT STATUS"' FILES EXAMPLES; do
    grep -qx ".SH $section" "$page" || fail "$page has no $section section"
  done
  commands=$(subcommands "$program")
  [ -n "$commands" ] || fail "$name --help lists no subcommand"
  for command in $commands; do
    "$program" "$command" --help > "$scratch/help" || fail "$name $command --help exited $?"
    [ -s "$scratch/help" ] || fail "$name $command --help printed nothing"
    grep -qF ".SS \"$name $command\"" "$page" || fail "$page has no section for $name $command"
    checked=$((checked + 1))
  done
done
for file in share/h4cal/boards/aprilgrid_6x6_30mm.yaml share/h4cal/boards/sim_camera_1024x768.yaml \
  share/doc/h4cal/README.md share/doc/h4cal/common/formats/README.md share/doc/h4cal/messages/README.md \
  share/h4cal/examples/robot.yaml; do
  [ -s "$prefix/$file" ] || fail "$file is not installed"
done
# The README's walkthrough names boards and the simulated camera bare (--board
# aprilgrid_6x6_30mm.yaml): from any folder, the installed programs find the installed file.
(cd "$scratch" && "$prefix/bin/h4cam" preview --source sim --board aprilgrid_6x6_30mm.yaml \
  --camera sim_camera_1024x768.yaml --count 1 > preview.log 2>&1) \
  || { cat "$scratch/preview.log"; fail "h4cam preview --board aprilgrid_6x6_30mm.yaml"; }
grep -q "board ok" "$scratch/preview.log" || fail "preview: $(cat "$scratch/preview.log")"
# The traffic watcher the walkthrough's step 4 names, installed with the types it compiles.
"$prefix/bin/h4cal-lcm-spy" --help > "$scratch/spy_help" 2>&1 || fail "h4cal-lcm-spy --help exited $?"
grep -q -- "--check LOGFILE" "$scratch/spy_help" || fail "h4cal-lcm-spy --help: $(cat "$scratch/spy_help")"
[ -s "$prefix/share/h4cal/messages/board_pose_t.lcm" ] || fail "the message types are not installed"
[ -s "$prefix/share/h4cal/messages/java/DecodeLog.java" ] || fail "DecodeLog.java is not installed"
echo "ok:   installed: --version on both, --help on $checked subcommands, man pages, boards, docs, h4cal-lcm-spy"

if ! command -v dpkg-deb > /dev/null; then
  echo "SKIPPED: the package part (dpkg-deb not found)"; exit 77
fi
arch=$(dpkg --print-architecture)
cpack --config "$build/CPackConfig-h4cal.cmake" -B "$scratch/out" > "$scratch/cpack.log" 2>&1 \
  || { cat "$scratch/cpack.log"; fail "cpack --config CPackConfig-h4cal.cmake"; }
deb=$scratch/out/h4cal_${version}_${arch}.deb
[ -f "$deb" ] || { ls -l "$scratch/out"; fail "expected $(basename "$deb")"; }
[ "$(dpkg-deb -f "$deb" Package)" = h4cal ] || fail "Package is not h4cal"
[ "$(dpkg-deb -f "$deb" Version)" = "$version" ] || fail "Version is not $version"
dpkg-deb -f "$deb" Depends | grep -q libc6 || fail "Depends lacks the shared libraries (shlibdeps)"
dpkg-deb -f "$deb" Conflicts | grep -qx h4cam || fail "Conflicts does not name h4cam"
dpkg-deb -c "$deb" > "$scratch/contents"
for file in usr/bin/h4cal usr/bin/h4cam usr/share/man/man1/h4cal.1 usr/share/man/man1/h4cam.1 \
  usr/share/h4cal/boards/aprilgrid_6x6_30mm.yaml usr/share/doc/h4cal/README.md; do
  grep -q " \./$file\$" "$scratch/contents" || fail "the package lacks /$file"
done
dpkg-deb -x "$deb" "$scratch/deb"
[ "$("$scratch/deb/usr/bin/h4cal" --version)" = "h4cal $version" ] || fail "packaged h4cal --version"
echo "PASS: $(basename "$deb"): h4cal, h4cam, man pages, boards, docs; Conflicts: h4cam"
