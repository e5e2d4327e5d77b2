# Sourced by the live tests (live_campaign, sequential_campaign and robot_bridge test
# scripts), which run programs as separate processes over UDP multicast, after they have set
# $src (the source tree) and $dir (their scratch directory):
#   source "$src/tests/integration/live_test_lib.sh"
#   enter_private_netns "$0" "$@"   # from here on, inside the namespace, in $dir
# Gives $scale ($H4_TEST_TIME_SCALE, default 1: the sanitizer build sets it,
# cmake/H4Sanitizers.cmake; every time limit of a live test is multiplied by it), $pids (the
# processes started, stopped on exit) and LCM_DEFAULT_URL (the project's group, ttl=0).

scale=${H4_TEST_TIME_SCALE:-1}
[[ "$scale" =~ ^[1-9][0-9]*$ ]] || { echo "FAIL: H4_TEST_TIME_SCALE='$scale' is not a positive integer"; exit 1; }

# enter_private_netns SCRIPT ARGS...: outside the namespace, empties $dir and runs SCRIPT
# again inside scripts/in-private-netns (loopback only, with a multicast route, so no
# datagram leaves the machine); when this machine cannot make one, exits 77 (ctest's skip)
# with the reason, also in $dir/SKIPPED (lcm_spy_test.sh reads it to skip for the same
# reason). Inside, it changes to $dir and arms the cleanup.
enter_private_netns() {
  if [ -z "${H4_IN_NETNS:-}" ]; then
    rm -rf "$dir"; mkdir -p "$dir"
    local netns=$src/scripts/in-private-netns status=0 reason
    reason=$("$netns" --check 2>&1) || status=$?
    if [ $status -eq 77 ]; then
      echo "$reason" > "$dir/SKIPPED"
      echo "SKIP: $reason"; exit 77
    fi
    [ $status -eq 0 ] || { echo "FAIL: $reason"; exit 1; }
    exec "$netns" env H4_IN_NETNS=1 "$@"
  fi
  pids=()
  trap stop_started_processes EXIT
  export LCM_DEFAULT_URL="udpm://239.255.76.67:7667?ttl=0"
  cd "$dir"
}

# Stops every process in $pids that still runs, and waits for them.
stop_started_processes() {
  for p in "${pids[@]}"; do kill "$p" 2> /dev/null || true; done
  wait 2> /dev/null || true
}
