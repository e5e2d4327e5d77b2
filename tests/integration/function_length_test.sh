#!/usr/bin/env bash
# Functions of a screen or less: no function definition longer than 60 lines in the
# identification core (host/identification) and than 80 lines anywhere else in host/ and
# firmware/, signature to closing brace. Counted on the clang-format layout: a definition
# starts at a column-0 line and ends at a column-0 "}"; a column-0 signature that ends in
# ";" before any "{" is a declaration, and a one-line body is skipped.
# Usage: function_length_test.sh SOURCE_DIR [CORE_LIMIT [LIMIT]]
set -uo pipefail
src=$1
core_limit=${2:-60}
limit=${3:-80}

long_functions() {  # limit, files...
  local max=$1; shift
  awk -v LIMIT="$max" '
    FNR == 1 { start = 0 }
    /^(namespace|using|#|\/\/|struct|class|enum|union|static_assert|extern|template)/ {
      if ($0 !~ /\{$/ || $0 ~ /^namespace/) { start = 0; next }
    }
    /^[A-Za-z_]/ && start == 0 { start = FNR; name = $0; opened = 0 }
    start > 0 && !opened && /\{/ { opened = 1 }
    start > 0 && !opened && /;[ \t]*$/ { start = 0; next }
    start > 0 && FNR == start && /\}[ \t;]*$/ { start = 0; next }
    /^}/ {
      if (start > 0 && $0 ~ /^}[ \t]*$/ && FNR - start + 1 > LIMIT)
        printf "%s:%d: %d lines: %s\n", FILENAME, start, FNR - start + 1, name
      start = 0
    }' "$@"
}

cd "$src" || exit 1
core=$(long_functions "$core_limit" host/identification/*.cpp)
rest=$(long_functions "$limit" $(find host firmware -name '*.cpp' -not -path 'host/identification/*' | sort))
if [ -n "$core$rest" ]; then
  [ -n "$core" ] && { echo "FAIL: functions in host/identification longer than $core_limit lines:"; echo "$core"; }
  [ -n "$rest" ] && { echo "FAIL: functions in host/ and firmware/ longer than $limit lines:"; echo "$rest"; }
  exit 1
fi
echo "PASS: every function is at most $core_limit lines in host/identification, $limit elsewhere in host/ and firmware/"
