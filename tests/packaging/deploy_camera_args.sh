#!/usr/bin/env bash
# scripts/deploy-camera's argument handling, without any network: ssh and scp are replaced
# by stand-ins that record their calls, and every case here must stop before using them.
#   deploy_camera_args.sh SOURCE_DIR
set -uo pipefail

script=$1/scripts/deploy-camera
scratch=$(mktemp -d "${TMPDIR:-/tmp}/h4cam-deploy-test.XXXXXX")
trap 'rm -rf "$scratch"' EXIT
mkdir -p "$scratch/bin"
for tool in ssh scp; do
  printf '#!/bin/sh\necho "%s $*" >> "%s/calls"\nexit 1\n' "$tool" "$scratch" > "$scratch/bin/$tool"
  chmod +x "$scratch/bin/$tool"
done

failures=0
run() {  # run EXPECTED_STATUS EXPECTED_TEXT ARGS...: status and text of stdout+stderr
  local want_status=$1 want_text=$2 status output
  shift 2
  output=$(PATH="$scratch/bin:$PATH" "$script" "$@" 2>&1)
  status=$?
  if [ $status -eq "$want_status" ] && grep -q -- "$want_text" <<< "$output"; then
    echo "ok:   deploy-camera $* -> exit $status"
  else
    echo "FAIL: deploy-camera $* -> exit $status (want $want_status and '$want_text'):"
    echo "$output"
    failures=$((failures + 1))
  fi
}

echo "not a package" > "$scratch/notes.txt"
echo "not a package either" > "$scratch/fake.deb"

run 0 "scripts/deploy-camera HOST \[--package FILE\]" --help
run 0 "ssh destination" -h
run 2 "missing HOST" --package "$scratch/fake.deb"
run 2 "missing HOST"
run 2 "unknown option '--force'" camera.local --force
run 2 "--package needs a file" camera.local --package
run 2 "one HOST only" camera1 camera2
run 2 "does not exist" camera.local --package "$scratch/missing.deb"
run 2 "is not a .deb file" camera.local --package "$scratch/notes.txt"
if command -v dpkg-deb >/dev/null; then
  run 2 "not a readable Debian package" camera.local --package "$scratch/fake.deb"
fi

if [ -s "$scratch/calls" ]; then
  echo "FAIL: ssh/scp were called:"
  cat "$scratch/calls"
  failures=$((failures + 1))
fi
[ $failures -eq 0 ] || { echo "$failures case(s) failed"; exit 1; }
echo "deploy-camera argument handling: all cases passed, no ssh/scp call"
